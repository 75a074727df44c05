#pragma once
// The random packing's portable random numbers (packing_random.cc): std::mt19937's raw output
// is fixed by the standard, the std::*_distribution classes are not, so the doubles are built
// here from raw 32-bit words and the same seed gives the same packing on every platform.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

namespace dembridge::dem::packing_detail
{
class Rng
{
public:
  explicit Rng(unsigned seed) : g_(seed) {}

  /// Uniform in [0, 1) with 53 random bits.
  double uniform()
  {
    const std::uint64_t a = std::uint64_t(g_()) >> 5, b = std::uint64_t(g_()) >> 6;
    return (double(a) * 67108864.0 + double(b)) * (1.0 / 9007199254740992.0);
  }

  /// Standard normal by Marsaglia's polar method (sqrt and log only: correctly rounded sqrt,
  /// and glibc's log is correctly rounded, so results agree across IEEE-754 platforms).
  double normal()
  {
    for (;;)
    {
      const double u = 2 * uniform() - 1, v = 2 * uniform() - 1, q = u * u + v * v;
      if (q > 0 && q < 1)
        return u * std::sqrt(-2 * std::log(q) / q);
    }
  }

  /// Uniform integer in [0, n).
  std::size_t index(std::size_t n)
  {
    return std::min<std::size_t>(n - 1, std::size_t(uniform() * double(n)));
  }

private:
  std::mt19937 g_;
};
} // namespace dembridge::dem::packing_detail
