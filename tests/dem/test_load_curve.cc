// Load-curve figures (dem/measurements/failure_measurements.h): the overall peak and the limit
// point of a load-deflection history, on curves whose answers are known by construction.
#include "dem/measurements/failure_measurements.h"
#include <gtest/gtest.h>
#include <stdexcept>
#include <vector>

namespace dem = dembridge::dem;

namespace
{
struct History
{
  std::vector<double> load, deflection;
  void add(double d, double p)
  {
    deflection.push_back(d);
    load.push_back(p);
  }
};

/// Linear rise P = d to the peak (1 N at 1 mm), then a linear branch to @p end_load at 3 mm,
/// sampled every 0.1 mm.
History rise_then_branch(double end_load)
{
  History h;
  for (int i = 0; i <= 30; ++i)
  {
    const double d = 0.1 * i;
    h.add(d, d <= 1 ? d : 1 + (end_load - 1) * (d - 1) / 2);
  }
  return h;
}
} // namespace

// Stable softening: the load falls gradually, so the limit point is the overall peak.
TEST(LoadCurve, LimitIsThePeakOfAStableSoftening)
{
  const History h = rise_then_branch(0.0);
  const dem::PeakLoad peak = dem::peak_of(h.load, h.deflection);
  const dem::PeakLoad limit = dem::limit_of(h.load, h.deflection);
  EXPECT_EQ(limit.index, peak.index);
  EXPECT_DOUBLE_EQ(limit.load, 1.0);
  EXPECT_DOUBLE_EQ(limit.displacement, 1.0);
}

// A snap: the load drops to a tenth at 1.1 mm and then rings up to 1.5 N at 1.3 mm. The overall
// peak is the spike; the limit point is the peak before the drop.
TEST(LoadCurve, LimitIgnoresTheRingingAfterASnap)
{
  History h;
  for (int i = 0; i <= 10; ++i)
    h.add(0.1 * i, 0.1 * i);
  h.add(1.1, 0.1);
  h.add(1.2, 0.8);
  h.add(1.3, 1.5);
  h.add(1.4, -0.6);
  const dem::PeakLoad peak = dem::peak_of(h.load, h.deflection);
  const dem::PeakLoad limit = dem::limit_of(h.load, h.deflection);
  EXPECT_DOUBLE_EQ(peak.load, 1.5);
  EXPECT_DOUBLE_EQ(peak.displacement, 1.3);
  EXPECT_DOUBLE_EQ(limit.load, 1.0);
  EXPECT_DOUBLE_EQ(limit.displacement, 1.0);
  EXPECT_EQ(limit.index, 10);
}

// Hardening to the end (no drop): the limit point is the last, largest record. Compression
// (negative loads) keeps its sign.
TEST(LoadCurve, NoDropAndCompression)
{
  History h = rise_then_branch(2.0);
  EXPECT_DOUBLE_EQ(dem::limit_of(h.load, h.deflection).load, 2.0);
  for (double& p : h.load)
    p = -p;
  EXPECT_DOUBLE_EQ(dem::limit_of(h.load, h.deflection).load, -2.0);
  EXPECT_EQ(dem::limit_of({}, {}).index, -1);
  EXPECT_THROW(dem::limit_of({1.0}, {}), std::invalid_argument);
}
