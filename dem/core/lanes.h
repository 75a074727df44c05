#pragma once
// Eight lanes of doubles, the number type of the SIMD loops over bonds (bonds/bond_block.h):
// GCC's vector extension, so that +, -, *, / and comparisons act lane by lane, scalars are
// broadcast, and the same source (a template over the number type) serves one bond (double)
// and eight (Lanes). With AVX-512 a Lanes value is one zmm register; elsewhere GCC splits it.
#include <cmath>
#include <cstdint>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace dembridge::dem
{
using Lanes = double __attribute__((vector_size(8 * sizeof(double))));
/// Integer lanes of a Lanes' width: comparisons give masks (-1 / 0) for `mask ? x : y`.
using LaneIndices = std::int64_t __attribute__((vector_size(8 * sizeof(std::int64_t))));

inline double lane_sqrt(double x)
{
  return std::sqrt(x);
}

inline Lanes lane_sqrt(Lanes x)
{
#if defined(__AVX512F__)
  return _mm512_sqrt_pd(x);
#else
  for (int j = 0; j < 8; ++j)
    x[j] = std::sqrt(x[j]);
  return x;
#endif
}
} // namespace dembridge::dem
