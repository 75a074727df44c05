#pragma once
// Random numbers keyed by a seed and a lattice node: each node draws from its own stream, so a
// grain's seed point and c-axis depend on where the grain is, not on how many grains were drawn
// before it (the same column in a particle region and in its full specimen). The stream is
// splitmix64 (Steele, Lea & Flood 2014, a bijective mix: neighbouring nodes get unrelated
// streams); doubles from its top 53 bits, so the same key gives the same numbers on every
// platform.
#include "dem/core/types.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace dembridge::dem
{
class KeyedRandom
{
public:
  KeyedRandom(std::uint64_t seed, std::uint64_t salt, long i, long j, long k = 0)
  {
    state_ = mix(mix(seed) ^ salt);
    for (long key : {i, j, k})
      state_ = mix(state_ ^ std::uint64_t(key));
  }

  /// U[0, 1).
  double uniform()
  {
    state_ = mix(state_);
    return double(state_ >> 11) * 0x1.0p-53;
  }
  /// N(0, 1) by Box-Muller.
  double standard_normal()
  {
    const double u1 = 1.0 - uniform(), u2 = uniform(); // u1 in (0, 1]
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  /// Uniform on the unit sphere (Archimedes: z uniform in [-1, 1]).
  Vec3 unit_vector()
  {
    const double z = 2.0 * uniform() - 1.0, t = 2.0 * std::numbers::pi * uniform();
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {s * std::cos(t), s * std::sin(t), z};
  }

  static std::uint64_t mix(std::uint64_t x)
  {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
  }

private:
  std::uint64_t state_;
};
} // namespace dembridge::dem
