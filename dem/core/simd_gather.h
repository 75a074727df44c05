#pragma once
// Gathering the 3- or 4-double records (Vec3, Quat) of W scattered particles into W-lane rows,
// for the SIMD loops over bonds (bonds/bond_block.h) and over the random packing's pairs
// (packing/overlap_forces.h). With AVX-512 each record is one (masked) vector load and the
// 8 x 4 transpose is done in registers: the hardware gather instruction, one element a lane, was
// slower on the development machine's AMD cores (and 8 scalar loads and stores per row were half
// of a bond block's time).
#include "dem/core/lanes.h"
#include <cstddef>
#include <cstdint>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace dembridge::dem
{
/// r[d][j] = data[n * index[j] + d] for d < n, j < 8: the records of 8 particles as lanes
/// (bonds/bond_block.h). For n = 3, r[3] holds junk.
template <int n>
[[gnu::always_inline]] inline void gather_lanes(const double* data, const std::int32_t* index,
                                                Lanes (&r)[4])
{
  static_assert(n == 3 || n == 4);
#if defined(__AVX512F__) && defined(__AVX512VL__)
  auto load = [&](int j)
  {
    const double* p = data + std::size_t(n) * std::size_t(index[j]);
    if constexpr (n == 3) // masked: the fourth double may lie past the array's end
      return _mm256_maskz_loadu_pd(0x7, p);
    else
      return _mm256_loadu_pd(p);
  };
  auto pair = [&](int j) // lane j in the low half, lane j + 4 in the high half
  { return _mm512_insertf64x4(_mm512_castpd256_pd512(load(j)), load(j + 4), 1); };
  const __m512d z0 = pair(0), z1 = pair(1), z2 = pair(2), z3 = pair(3);
  const __m512d t0 = _mm512_unpacklo_pd(z0, z1); // r0c0 r1c0 r0c2 r1c2 | r4c0 r5c0 r4c2 r5c2
  const __m512d t1 = _mm512_unpackhi_pd(z0, z1); // the same with c1, c3
  const __m512d t2 = _mm512_unpacklo_pd(z2, z3); // r2c0 r3c0 r2c2 r3c2 | r6c0 r7c0 ...
  const __m512d t3 = _mm512_unpackhi_pd(z2, z3);
  const __m512i even = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i odd = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  r[0] = _mm512_permutex2var_pd(t0, even, t2);
  r[1] = _mm512_permutex2var_pd(t1, even, t3);
  r[2] = _mm512_permutex2var_pd(t0, odd, t2);
  r[3] = _mm512_permutex2var_pd(t1, odd, t3);
#else
  for (int j = 0; j < 8; ++j)
  {
    const double* p = data + std::size_t(n) * std::size_t(index[j]);
    for (int d = 0; d < n; ++d)
      r[d][j] = p[d];
  }
#endif
}

/// rows[d][j] = data[n * index[j] + d] for d < n, j < W: the records (3 or 4 doubles) of W
/// particles turned into n lane-major rows. Writes 4 rows; for n = 3 the fourth holds junk (a
/// caller may let its next gather overwrite it). AVX-512: loads and an in-register transpose;
/// otherwise, or for another W, scalar copies.
template <int W, int n>
[[gnu::always_inline]] inline void gather_rows(const double* data, const std::int32_t* index,
                                               double (*rows)[W])
{
  static_assert(n == 3 || n == 4);
#if defined(__AVX512F__) && defined(__AVX512VL__)
  if constexpr (W == 8)
  {
    Lanes r[4];
    gather_lanes<n>(data, index, r);
    for (int d = 0; d < 4; ++d)
      __builtin_memcpy(rows[d], &r[d], sizeof r[d]);
    return;
  }
#endif
  for (int j = 0; j < W; ++j)
  {
    std::size_t i = std::size_t(index[j]);
    asm("" : "+r"(i)); // keeps this loop scalar (no emulated gathers)
    const double* p = data + std::size_t(n) * i;
    for (int d = 0; d < n; ++d)
      rows[d][j] = p[d];
  }
}
} // namespace dembridge::dem
