// The running summary of a per-step series (dem/core/running_series.h; the FE dynamics
// energies): first value, range and least-squares line against the step index, updated one
// value at a time, against exact values and the two-pass formula in long double.
#include "dem/core/running_series.h"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

using dembridge::dem::RunningSeries;

// A straight line v_k = a + b k: the fitted change over n values is b n, the range b (n - 1).
TEST(RunningSeries, LineIsFittedExactly)
{
  RunningSeries s;
  const double a = 2.5, b = 3e-3;
  const int n = 1000;
  for (int k = 0; k < n; ++k)
    s.add(a + b * k);
  EXPECT_EQ(s.count, n);
  EXPECT_EQ(s.first, a);
  EXPECT_NEAR(s.fitted_change(), b * n, 1e-12 * b * n);
  EXPECT_NEAR(s.relative_range(), b * (n - 1) / a, 1e-14);
}

// An energy as the FE runs see it: H_0 (1 + drift k / n + an oscillation 50x the drift). The
// summary's drift against the two-pass least-squares slope in long double: within 1e-18 of H_0
// (the fitted drift is 6.3e-13 of H_0, the oscillation tilting the line; the changes v_k - v_0
// are exact, so the fit is far closer: 4e-27 here, against 6e-16 without that shift); the
// range exact.
TEST(RunningSeries, DriftMatchesTheTwoPassSlope)
{
  const double h0 = 7.0, drift = 2e-12;
  const int n = 1000;
  std::vector<double> v(n);
  RunningSeries s;
  for (int k = 0; k < n; ++k)
  {
    v[k] = h0 * (1 + drift * k / n + 1e-10 * std::sin(0.37 * k));
    s.add(v[k]);
  }
  long double mk = 0, mv = 0, sxy = 0, sxx = 0;
  for (int k = 0; k < n; ++k)
  {
    mk += (long double)k / n;
    mv += (long double)v[k] / n;
  }
  for (int k = 0; k < n; ++k)
  {
    sxy += (k - mk) * (v[k] - mv);
    sxx += (k - mk) * (k - mk);
  }
  const double reference = double(sxy / sxx * n) / h0;
  EXPECT_NEAR(s.fitted_change() / h0, reference, 1e-18);
  std::printf("fitted drift %.6e, two-pass %.6e, difference %.2e (of H_0)\n",
              s.fitted_change() / h0, reference, s.fitted_change() / h0 - reference);
  EXPECT_GT(std::abs(reference), 5e-13); // a drift far above the tolerance
  double lo = v[0], hi = v[0];
  for (double x : v)
    lo = std::min(lo, x), hi = std::max(hi, x);
  EXPECT_EQ(s.relative_range(), (hi - lo) / h0);
}

// Fewer than two values have no line.
TEST(RunningSeries, OneValueHasNoSlope)
{
  RunningSeries s;
  s.add(4.0);
  EXPECT_EQ(s.fitted_change(), 0.0);
  EXPECT_EQ(s.relative_range(), 0.0);
}
