#pragma once
// The unified bond law (bond_kernel.h) on a block of W consecutive bonds at once, in SIMD lanes
// (AVX-512: 8 doubles). The lanes gather their particles' positions, orientations and
// velocities, evaluate the very same bond_law (inlined, so every lane computes bit for bit what
// the scalar kernel computes for its bond, up to the compiler's fused multiply-adds), and leave
// the contact forces in a lane-major block. For the scatter they are turned (in registers) into
// one record per bond end, what the bond adds to that particle, and the caller adds the records
// to the particles one bond at a time, each as a few whole vectors (two bonds of a block often
// share a particle, so the scatter cannot be one vector store across lanes). Bonds past the
// end of a range (m < W) repeat its last bond and are ignored.
#include "dem/bonds/bond_kernel.h"
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/core/simd_gather.h"
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace dembridge::dem
{
#ifndef BOND_BLOCK_W
#define BOND_BLOCK_W 8
#endif
inline constexpr int bond_block_width = BOND_BLOCK_W;

static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Quat) == 4 * sizeof(double),
              "the bond law reads Vec3 and Quat arrays as plain doubles");

/// The doubles of a Vec3 or Quat array; null for an empty one (why: v.data()->data() would
/// dereference a null pointer there, which UBSan reports on a specimen without bonds).
template <class T> const double* raw_doubles(const std::vector<T>& v)
{
  return reinterpret_cast<const double*>(v.data());
}

/// Raw views of the arrays the bond law reads (Eigen's storage: Vec3 = 3 doubles, Quat = x, y,
/// z, w).
struct BondLawArrays
{
  const double *x, *q, *v, *w;
  const std::int32_t *a, *b;
  const double *L0, *e0, *kn, *ks, *ktor, *kben, *s, *ct, *cr;

  BondLawArrays(const ParticleStore& p, const BondStore& bonds)
      : x(raw_doubles(p.position)), q(raw_doubles(p.orientation)), v(raw_doubles(p.velocity)),
        w(raw_doubles(p.angular_velocity)), a(bonds.a.data()), b(bonds.b.data()),
        L0(bonds.rest_length.data()), e0(raw_doubles(bonds.rest_axis)), kn(bonds.kn.data()),
        ks(bonds.ks.data()), ktor(bonds.ktor.data()), kben(bonds.kben.data()),
        s(bonds.contact_fraction.data()), ct(bonds.damping_force.data()),
        cr(bonds.damping_moment.data())
  {
  }
};

/// What a bond adds to each of its particles, as one record of doubles (the explicit solver's
/// per-particle sums have the same layout): force 0-2, moment 3-5, and with dashpots their
/// dashpot parts, force 6-8 and moment 9-11; without dashpots 6-7 are padding (zero), so that a
/// record is whole 256-bit vectors.
template <bool dashpots> inline constexpr int particle_record_size = dashpots ? 12 : 8;
inline constexpr int particle_record_capacity = 12;

/// A particle record (particle_record_size doubles) in registers: the scatter's sum for the
/// lower particle of a run of bonds, and the adds of whole records (32-byte aligned: the
/// block's rows and the solver's sums are).
template <int S> struct ParticleRecord
{
  static_assert(S % 4 == 0);
#if defined(__AVX__)
  __m256d v[S / 4];
  void load(const double* p)
  {
    for (int i = 0; i < S / 4; ++i)
      v[i] = _mm256_load_pd(p + 4 * i);
  }
  void store(double* p) const
  {
    for (int i = 0; i < S / 4; ++i)
      _mm256_store_pd(p + 4 * i, v[i]);
  }
  /// this += c * r (scaled) or this += r
  template <bool scaled> void add(const double* r, double c)
  {
    for (int i = 0; i < S / 4; ++i)
      v[i] = scaled
                 ? _mm256_add_pd(v[i], _mm256_mul_pd(_mm256_set1_pd(c), _mm256_load_pd(r + 4 * i)))
                 : _mm256_add_pd(v[i], _mm256_load_pd(r + 4 * i));
  }
#else
  double v[S];
  void load(const double* p)
  {
    std::copy(p, p + S, v);
  }
  void store(double* p) const
  {
    std::copy(v, v + S, p);
  }
  template <bool scaled> void add(const double* r, double c)
  {
    for (int i = 0; i < S; ++i)
      v[i] += scaled ? c * r[i] : r[i];
  }
#endif
};

/// Contact forces of a block, lane j = bond k0 + j.
struct alignas(64) BondBlock
{
  static constexpr int W = bond_block_width;
  double Fc[3][W], Mc[3][W], Fd[3][W], Md[3][W], e[3][W];
  double ra[W], rb[W], strain_energy[W];
  /// The particle resultants' moments (bond_resultants): Ma = -Mc - ra e x Fc on a and
  /// Mb = Mc + rb e x Fc on b, and the same of the dashpot parts (zero without dashpots), so
  /// that the scatter only adds (the forces are -Fc on a and Fc on b).
  double Ma[3][W], Mb[3][W], Mda[3][W], Mdb[3][W];
  /// Bond j's records (particle_record_size) for its lower- and higher-numbered particle:
  /// lower[j] = (-Fc, Ma, -Fd, Mda) when a < b, else (Fc, Mb, Fd, Mdb); upper[j] the other end.
  alignas(32) double lower[W][particle_record_capacity];
  alignas(32) double upper[W][particle_record_capacity];

  /// Lane j as the scalar kernel's output.
  void lane(int j, BondForces& f) const
  {
    for (int d = 0; d < 3; ++d)
    {
      f.Fc[d] = Fc[d][j], f.Mc[d] = Mc[d][j], f.Fd[d] = Fd[d][j], f.Md[d] = Md[d][j];
      f.e[d] = e[d][j];
    }
    f.ra = ra[j], f.rb = rb[j], f.strain_energy = strain_energy[j];
  }
};

/// The lanes of a block: bond k0 + j's law in lane j (full: m = W and k = j; else bonds past m
/// repeat the last), from the gathered rows g and the constants at k0.
template <bool dashpots, bool full, int W, int n_rows>
[[gnu::always_inline]] inline void
bond_lanes(const double (&g)[n_rows][W], const double* L0, const double* E0, const double* kn,
           const double* ks, const double* ktor, const double* kben, const double* s,
           const double* ct, const double* cr, int m, BondBlock& out)
{
#pragma GCC ivdep
  for (int j = 0; j < W; ++j)
  {
    const long k = full ? long(j) : long(std::min(j, m - 1));
    const BondConstants c{L0[k],   Vec3(E0[3 * k], E0[3 * k + 1], E0[3 * k + 2]),
                          kn[k],   ks[k],
                          ktor[k], kben[k],
                          s[k],    ct[k],
                          cr[k]};
    BondForces f;
    const double xa[3] = {g[0][j], g[1][j], g[2][j]}, xb[3] = {g[3][j], g[4][j], g[5][j]};
    const double qa[4] = {g[6][j], g[7][j], g[8][j], g[9][j]};
    const double qb[4] = {g[10][j], g[11][j], g[12][j], g[13][j]};
    double va[3] = {0, 0, 0}, vb[3] = {0, 0, 0}, wa[3] = {0, 0, 0}, wb[3] = {0, 0, 0};
    if constexpr (dashpots)
      for (int d = 0; d < 3; ++d)
        va[d] = g[14 + d][j], vb[d] = g[17 + d][j], wa[d] = g[20 + d][j], wb[d] = g[23 + d][j];
    bond_law<dashpots>(xa, xb, qa, qb, va, vb, wa, wb, c, f);
    out.Fc[0][j] = f.Fc[0], out.Fc[1][j] = f.Fc[1], out.Fc[2][j] = f.Fc[2];
    out.Mc[0][j] = f.Mc[0], out.Mc[1][j] = f.Mc[1], out.Mc[2][j] = f.Mc[2];
    out.Fd[0][j] = f.Fd[0], out.Fd[1][j] = f.Fd[1], out.Fd[2][j] = f.Fd[2];
    out.Md[0][j] = f.Md[0], out.Md[1][j] = f.Md[1], out.Md[2][j] = f.Md[2];
    out.e[0][j] = f.e[0], out.e[1][j] = f.e[1], out.e[2][j] = f.e[2];
    out.ra[j] = f.ra, out.rb[j] = f.rb, out.strain_energy[j] = f.strain_energy;
    // the resultants' moments (bond_kernel.h)
    double ma[3], mb[3];
    resultant_moments(f.Fc, f.Mc, f, ma, mb);
    for (int d = 0; d < 3; ++d)
      out.Ma[d][j] = ma[d], out.Mb[d][j] = mb[d];
    if constexpr (dashpots)
    {
      resultant_moments(f.Fd, f.Md, f, ma, mb);
      for (int d = 0; d < 3; ++d)
        out.Mda[d][j] = ma[d], out.Mdb[d][j] = mb[d];
    }
  }
}

/// The records of 8 bonds, 4 values each: rows r[0..3] (value d of bonds 0..7) to
/// dst[j][offset + d]. An in-register 4 x 8 transpose.
#if defined(__AVX512F__) && defined(__AVX512VL__)
[[gnu::always_inline]] inline void
store_records4(const __m512d (&r)[4], double (*dst)[particle_record_capacity], int offset)
{
  const __m512d t0 = _mm512_unpacklo_pd(r[0], r[1]); // r0_0 r1_0 | r0_2 r1_2 | r0_4 .. | r0_6 ..
  const __m512d t1 = _mm512_unpackhi_pd(r[0], r[1]); // the same for bonds 1, 3, 5, 7
  const __m512d t2 = _mm512_unpacklo_pd(r[2], r[3]);
  const __m512d t3 = _mm512_unpackhi_pd(r[2], r[3]);
  const __m512i first = _mm512_set_epi64(11, 10, 3, 2, 9, 8, 1, 0);    // bonds 0 | 2 of a pair
  const __m512i second = _mm512_set_epi64(15, 14, 7, 6, 13, 12, 5, 4); // bonds 4 | 6
  const __m512d b02 = _mm512_permutex2var_pd(t0, first, t2);
  const __m512d b46 = _mm512_permutex2var_pd(t0, second, t2);
  const __m512d b13 = _mm512_permutex2var_pd(t1, first, t3);
  const __m512d b57 = _mm512_permutex2var_pd(t1, second, t3);
  _mm256_store_pd(dst[0] + offset, _mm512_castpd512_pd256(b02));
  _mm256_store_pd(dst[2] + offset, _mm512_extractf64x4_pd(b02, 1));
  _mm256_store_pd(dst[4] + offset, _mm512_castpd512_pd256(b46));
  _mm256_store_pd(dst[6] + offset, _mm512_extractf64x4_pd(b46, 1));
  _mm256_store_pd(dst[1] + offset, _mm512_castpd512_pd256(b13));
  _mm256_store_pd(dst[3] + offset, _mm512_extractf64x4_pd(b13, 1));
  _mm256_store_pd(dst[5] + offset, _mm512_castpd512_pd256(b57));
  _mm256_store_pd(dst[7] + offset, _mm512_extractf64x4_pd(b57, 1));
}
#endif

/// The block's particle records (BondBlock::lower, upper) from its resultant rows: each end's
/// values chosen by which end has the lower index, the forces negated on a (the scatter then
/// only adds whole records; x - y and x + (-y) are the same double). One bond at a time: the
/// reference for the lanes' version below, and the path of builds without AVX-512.
template <bool dashpots, int W>
inline void particle_records_scalar(const std::int32_t* ia, const std::int32_t* ib, BondBlock& out)
{
  for (int j = 0; j < W; ++j)
  {
    const bool a_lower = ia[j] < ib[j];
    double* lo = out.lower[j];
    double* up = out.upper[j];
    auto ends = [&](const double(*F)[W], const double(*Ma)[W], const double(*Mb)[W], int at)
    {
      for (int d = 0; d < 3; ++d)
      {
        const double f = F[d][j];
        lo[at + d] = a_lower ? -f : f, up[at + d] = a_lower ? f : -f;
        lo[at + 3 + d] = a_lower ? Ma[d][j] : Mb[d][j];
        up[at + 3 + d] = a_lower ? Mb[d][j] : Ma[d][j];
      }
    };
    ends(out.Fc, out.Ma, out.Mb, 0);
    if constexpr (dashpots)
      ends(out.Fd, out.Mda, out.Mdb, 6);
    else
      lo[6] = lo[7] = up[6] = up[7] = 0.0;
  }
}

/// particle_records_scalar in AVX-512 lanes: the choices by a mask, the records by 4 x 8
/// transposes in registers.
template <bool dashpots, int W>
[[gnu::always_inline]] inline void particle_records(const std::int32_t* ia, const std::int32_t* ib,
                                                    BondBlock& out)
{
#if defined(__AVX512F__) && defined(__AVX512VL__)
  if constexpr (W == 8)
  {
    constexpr int S = particle_record_size<dashpots>;
    const __mmask8 a_lower =
        _mm256_cmplt_epi32_mask(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(ia)),
                                _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ib)));
    const __m512i sign = _mm512_set1_epi64(std::int64_t(0x8000000000000000ull));
    auto negated = [&](__m512d x)
    { return _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(x), sign)); };
    __m512d lo[S], up[S];
    auto ends = [&](const double(*F)[W], const double(*Ma)[W], const double(*Mb)[W], int at)
    {
      for (int d = 0; d < 3; ++d)
      {
        const __m512d f = _mm512_load_pd(F[d]), nf = negated(f);
        const __m512d ma = _mm512_load_pd(Ma[d]), mb = _mm512_load_pd(Mb[d]);
        lo[at + d] = _mm512_mask_blend_pd(a_lower, f, nf); // blend: the second where set
        up[at + d] = _mm512_mask_blend_pd(a_lower, nf, f);
        lo[at + 3 + d] = _mm512_mask_blend_pd(a_lower, mb, ma);
        up[at + 3 + d] = _mm512_mask_blend_pd(a_lower, ma, mb);
      }
    };
    ends(out.Fc, out.Ma, out.Mb, 0);
    if constexpr (dashpots)
      ends(out.Fd, out.Mda, out.Mdb, 6);
    else
      lo[6] = lo[7] = up[6] = up[7] = _mm512_setzero_pd();
    for (int at = 0; at < S; at += 4)
    {
      store_records4({lo[at], lo[at + 1], lo[at + 2], lo[at + 3]}, out.lower, at);
      store_records4({up[at], up[at + 1], up[at + 2], up[at + 3]}, out.upper, at);
    }
    return;
  }
#endif
  particle_records_scalar<dashpots, W>(ia, ib, out);
}

/// Evaluates bonds k0 .. k0 + m - 1 (m <= W) into @p out.
template <bool dashpots>
inline void bond_law_block(const BondLawArrays& in, std::size_t k0, int m, BondBlock& out)
{
  constexpr int W = BondBlock::W;
  const double *X = in.x, *Q = in.q, *V = in.v, *Wv = in.w, *E0 = in.e0;
  const std::int32_t *A = in.a + k0, *B = in.b + k0;
  const double *L0 = in.L0 + k0, *kn = in.kn + k0, *ks = in.ks + k0, *ktor = in.ktor + k0;
  const double *kben = in.kben + k0, *s = in.s + k0, *ct = in.ct + k0, *cr = in.cr + k0;
  E0 += 3 * k0;
  // Gather: the particle data of the block's bonds into lane-major rows.
  constexpr int n_rows = dashpots ? 27 : 14; // one spare row: gather_rows writes 4 per Vec3
  alignas(64) double g[n_rows][W];
  std::int32_t ia[W], ib[W];
  // why: a full block's indices are plain vector loads; the clamped index of a partial block
  // compiles to hardware gathers, which cost ~7 % of a step on these AMD cores when used always
  if (m == W)
    for (int j = 0; j < W; ++j)
      ia[j] = A[j], ib[j] = B[j];
  else
    for (int j = 0; j < W; ++j)
    {
      const int k = std::min(j, m - 1);
      ia[j] = A[k], ib[j] = B[k];
    }
  // Rows in this order, so that each Vec3's spare fourth row is overwritten by the next
  // quantity: xa 0-2, xb 3-5, qa 6-9, qb 10-13, va 14-16, vb 17-19, wa 20-22, wb 23-25.
  gather_rows<W, 3>(X, ia, g + 0);
  gather_rows<W, 3>(X, ib, g + 3);
  gather_rows<W, 4>(Q, ia, g + 6);
  gather_rows<W, 4>(Q, ib, g + 10);
  if constexpr (dashpots)
  {
    gather_rows<W, 3>(V, ia, g + 14);
    gather_rows<W, 3>(V, ib, g + 17);
    gather_rows<W, 3>(Wv, ia, g + 20);
    gather_rows<W, 3>(Wv, ib, g + 23);
  }
  // why: a full block reads its constants at k = j (contiguous vector loads in 64-bit lanes);
  // a clamped index makes them emulated gathers and, in 32-bit ints, halves the vector width
  if (m == W)
    bond_lanes<dashpots, true>(g, L0, E0, kn, ks, ktor, kben, s, ct, cr, W, out);
  else
    bond_lanes<dashpots, false>(g, L0, E0, kn, ks, ktor, kben, s, ct, cr, m, out);
  particle_records<dashpots, W>(ia, ib, out);
}
} // namespace dembridge::dem
