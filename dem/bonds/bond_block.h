#pragma once
// The unified bond law (bond_kernel.h) on a block of 8 consecutive bonds at once, in SIMD lanes
// (core/lanes.h; with AVX-512 one zmm register a quantity). The block gathers its particles'
// positions, orientations and velocities straight into registers (an 8 x 4 transpose a
// quantity), evaluates the very same law source as the scalar kernel (bond_law_of, a template
// over the number type, so each lane computes what the scalar kernel computes for its bond, up
// to the compiler's fused multiply-adds), and turns the resultants into one record per bond
// end, what the bond adds to that particle (masks choose the lower end, 4 x 8 transposes make
// the records). Only the records are stored, and on steps that read them the contact forces as
// lane-major rows. The caller adds the records to the particles one bond at a time, each as a
// few whole vectors (two bonds of a block often share a particle, so the scatter cannot be one
// vector store across lanes). Bonds past the end of a range (m < 8) repeat its last bond and
// are ignored. Why registers: the law's loop auto-vectorised over rows in memory spent about
// half of its samples on the rows' loads and stores (gathered inputs, outputs, moments).
#include "dem/bonds/bond_kernel.h"
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/core/simd_gather.h"
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace dembridge::dem
{
inline constexpr int bond_block_width = 8; // one Lanes vector

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
  /// Smooth joints (smooth_joint.h): the classes (the weak-plane bonds are joints where
  /// plane_joints, the basal bonds where basal_normal is set), the planes' normal N and the
  /// basal bonds' per-bond normals; null, false and zero without joints.
  const BondClass* bond_class;
  bool plane_joints;
  double joint_normal[3];
  const double* basal_normal;

  BondLawArrays(const ParticleStore& p, const BondStore& bonds)
      : x(raw_doubles(p.position)), q(raw_doubles(p.orientation)), v(raw_doubles(p.velocity)),
        w(raw_doubles(p.angular_velocity)), a(bonds.a.data()), b(bonds.b.data()),
        L0(bonds.rest_length.data()), e0(raw_doubles(bonds.rest_axis)), kn(bonds.kn.data()),
        ks(bonds.ks.data()), ktor(bonds.ktor.data()), kben(bonds.kben.data()),
        s(bonds.contact_fraction.data()), ct(bonds.damping_force.data()),
        cr(bonds.damping_moment.data()),
        bond_class(bonds.has_smooth_joints() ? bonds.bond_class.data() : nullptr),
        plane_joints(bonds.has_plane_joints()), joint_normal{},
        basal_normal(bonds.has_basal_joints() ? raw_doubles(bonds.basal_normal) : nullptr)
  {
    if (plane_joints)
      for (int d = 0; d < 3; ++d)
        joint_normal[d] = (*bonds.smooth_joint_normal)[d];
  }

  /// Whether bond k is a smooth joint, and then its normal N (unsigned) in @p N.
  bool joint_of(std::size_t k, double* N) const
  {
    if (bond_class[k] == BondClass::weak_plane && plane_joints)
    {
      N[0] = joint_normal[0], N[1] = joint_normal[1], N[2] = joint_normal[2];
      return true;
    }
    if (bond_class[k] == BondClass::basal && basal_normal)
    {
      N[0] = basal_normal[3 * k], N[1] = basal_normal[3 * k + 1], N[2] = basal_normal[3 * k + 2];
      return true;
    }
    return false;
  }
};

/// What a bond adds to each of its particles, as one record of doubles (the explicit solver's
/// per-particle sums have the same layout): force 0-2, moment 3-5, and with dashpots their
/// dashpot parts, force 6-8 and moment 9-11; without dashpots 6-7 are padding (zero), so that a
/// record is whole 256-bit vectors.
template <bool dashpots> inline constexpr int particle_record_size = dashpots ? 12 : 8;
inline constexpr int particle_record_capacity = particle_record_size<true>;
/// Where a record's parts start.
inline constexpr int record_force = 0, record_moment = 3, record_dashpot_force = 6,
                     record_dashpot_moment = 9;

/// A particle record (particle_record_size doubles) in registers: the scatter's sum for the
/// lower particle of a run of bonds, and the adds of whole records, as 256-bit vectors (GCC's
/// vector extension; the block's records and the solver's sums are 32-byte aligned).
template <int S> struct ParticleRecord
{
  static_assert(S % 4 == 0);
  using Quad = double __attribute__((vector_size(4 * sizeof(double)), may_alias));
  Quad v[S / 4];
  void load(const double* p)
  {
    for (int i = 0; i < S / 4; ++i)
      v[i] = *reinterpret_cast<const Quad*>(p + 4 * i);
  }
  void store(double* p) const
  {
    for (int i = 0; i < S / 4; ++i)
      *reinterpret_cast<Quad*>(p + 4 * i) = v[i];
  }
  /// this += c * r (scaled) or this += r
  template <bool scaled> void add(const double* r, double c)
  {
    for (int i = 0; i < S / 4; ++i)
    {
      const Quad x = *reinterpret_cast<const Quad*>(r + 4 * i);
      if constexpr (scaled)
        v[i] += c * x;
      else
        v[i] += x;
    }
  }
};

/// A block's output, lane j = bond k0 + j: the records for the scatter, and on steps that read
/// them (records, failure laws) the contact forces as lane-major rows.
struct alignas(64) BondBlock
{
  static constexpr int W = bond_block_width;
  double Fc[3][W], Mc[3][W], Fd[3][W], Md[3][W], e[3][W];
  double n[3][W]; ///< the failure check's axis (BondForcesOf::n); written with smooth joints only
  double ra[W], rb[W], strain_energy[W];
  /// Bond j's records (particle_record_size) for its lower- and higher-numbered particle:
  /// lower[j] = (-Fc, Ma, -Fd, Mda) when a < b, else (Fc, Mb, Fd, Mdb); upper[j] the other end,
  /// with Ma = -Mc - ra e x Fc, Mb = Mc + rb e x Fc (bond_resultants) and likewise the dashpot
  /// parts' moments (x - y and x + (-y) are the same double, so the scatter only adds).
  alignas(32) double lower[W][particle_record_capacity];
  alignas(32) double upper[W][particle_record_capacity];

  /// Lane j as the scalar kernel's output (the rows must have been written).
  void lane(int j, BondForces& f) const
  {
    for (int d = 0; d < 3; ++d)
    {
      f.Fc[d] = Fc[d][j], f.Mc[d] = Mc[d][j], f.Fd[d] = Fd[d][j], f.Md[d] = Md[d][j];
      f.e[d] = e[d][j];
    }
    f.ra = ra[j], f.rb = rb[j], f.strain_energy = strain_energy[j];
  }
  /// Lane j's failure axis (written by a block with smooth joints only).
  void lane_axis(int j, BondForces& f) const
  {
    for (int d = 0; d < 3; ++d)
      f.n[d] = n[d][j];
  }
};

/// What each end of the block's bonds receives, as lanes: force, moment and with dashpots their
/// dashpot parts (the rows of BondBlock::lower / upper before the transpose).
template <int S> struct EndLanes
{
  Lanes lower[S], upper[S];
};

/// The ends' lanes from the resultants: which end is the lower one by a compare of the indices
/// (a lane mask), the force negated on a.
template <bool dashpots>
[[gnu::always_inline]] inline EndLanes<particle_record_size<dashpots>>
end_lanes(LaneIndices ia, LaneIndices ib, const BondForcesOf<Lanes>& f, const Lanes (&ma)[3],
          const Lanes (&mb)[3], const Lanes (&mda)[3], const Lanes (&mdb)[3])
{
  EndLanes<particle_record_size<dashpots>> r;
  const LaneIndices a_lower = ia < ib; // -1 where a is the lower end
  auto ends = [&](const Lanes* F, const Lanes* Ma, const Lanes* Mb, int at)
  {
    for (int d = 0; d < 3; ++d)
    {
      const Lanes nF = -F[d];
      r.lower[at + d] = a_lower ? nF : F[d], r.upper[at + d] = a_lower ? F[d] : nF;
      r.lower[at + 3 + d] = a_lower ? Ma[d] : Mb[d];
      r.upper[at + 3 + d] = a_lower ? Mb[d] : Ma[d];
    }
  };
  ends(f.Fc, ma, mb, record_force); // the moment 3 after its force, as record_moment
  if constexpr (dashpots)
    ends(f.Fd, mda, mdb, record_dashpot_force);
  else
    for (int d = record_dashpot_force; d < particle_record_size<false>; ++d) // padding
      r.lower[d] = r.upper[d] = Lanes{};
  return r;
}

/// Rows (value d of bonds 0..7) to records, rows[d][j] -> dst[j][d], one value at a time: the
/// reference the transposes below are tested against, and the path without AVX-512.
template <int S>
inline void store_records_scalar(const Lanes (&rows)[S], double (*dst)[particle_record_capacity])
{
  for (int j = 0; j < 8; ++j)
    for (int d = 0; d < S; ++d)
      dst[j][d] = rows[d][j];
}

/// Rows (value d of bonds 0..7) to records: rows[d][j] -> dst[j][d], d < S. AVX-512: 4 x 8
/// transposes in registers.
template <int S>
[[gnu::always_inline]] inline void store_records(const Lanes (&rows)[S],
                                                 double (*dst)[particle_record_capacity])
{
#if defined(__AVX512F__) && defined(__AVX512VL__)
  for (int at = 0; at < S; at += 4)
  {
    const __m512d t0 = _mm512_unpacklo_pd(rows[at], rows[at + 1]); // r0_0 r1_0 | r0_2 r1_2 | ..
    const __m512d t1 = _mm512_unpackhi_pd(rows[at], rows[at + 1]); // bonds 1, 3, 5, 7
    const __m512d t2 = _mm512_unpacklo_pd(rows[at + 2], rows[at + 3]);
    const __m512d t3 = _mm512_unpackhi_pd(rows[at + 2], rows[at + 3]);
    const __m512i first = _mm512_set_epi64(11, 10, 3, 2, 9, 8, 1, 0);    // bonds 0 | 2 of a pair
    const __m512i second = _mm512_set_epi64(15, 14, 7, 6, 13, 12, 5, 4); // bonds 4 | 6
    const __m512d b02 = _mm512_permutex2var_pd(t0, first, t2);
    const __m512d b46 = _mm512_permutex2var_pd(t0, second, t2);
    const __m512d b13 = _mm512_permutex2var_pd(t1, first, t3);
    const __m512d b57 = _mm512_permutex2var_pd(t1, second, t3);
    _mm256_store_pd(dst[0] + at, _mm512_castpd512_pd256(b02));
    _mm256_store_pd(dst[2] + at, _mm512_extractf64x4_pd(b02, 1));
    _mm256_store_pd(dst[4] + at, _mm512_castpd512_pd256(b46));
    _mm256_store_pd(dst[6] + at, _mm512_extractf64x4_pd(b46, 1));
    _mm256_store_pd(dst[1] + at, _mm512_castpd512_pd256(b13));
    _mm256_store_pd(dst[3] + at, _mm512_extractf64x4_pd(b13, 1));
    _mm256_store_pd(dst[5] + at, _mm512_castpd512_pd256(b57));
    _mm256_store_pd(dst[7] + at, _mm512_extractf64x4_pd(b57, 1));
  }
#else
  store_records_scalar<S>(rows, dst);
#endif
}

/// Eight values from p[0..m) as lanes, lanes past m repeating p[m - 1].
[[gnu::always_inline]] inline Lanes load_lanes(const double* p, int m)
{
  Lanes v;
  if (m == 8)
    __builtin_memcpy(&v, p, sizeof v);
  else
    for (int j = 0; j < 8; ++j)
      v[j] = p[std::min(j, m - 1)];
  return v;
}

/// The law on a block's lanes; with `smooth`, the weak-plane and basal bonds among them are
/// smooth joints where the store has their normals (smooth_joint.h: n_0 = sign(N . e_0) N,
/// eq. 5, N the plane's normal or the basal bond's own), and f.n is written for every lane.
template <bool dashpots, bool smooth>
[[gnu::always_inline]] inline void
block_law(const BondLawArrays& in, std::size_t k0, const std::int32_t* bond, const Lanes* xa,
          const Lanes* xb, const Lanes* qa, const Lanes* qb, const Lanes* va, const Lanes* vb,
          const Lanes* wa, const Lanes* wb, const Lanes* e0, const LawConstants<Lanes>& c,
          BondForcesOf<Lanes>& f)
{
  if constexpr (smooth)
  {
    JointOf<Lanes> joint;
    Lanes N[3]{};
    bool any = false;
    for (int j = 0; j < BondBlock::W; ++j)
    {
      double n[3] = {0, 0, 0};
      const bool on = in.joint_of(k0 + std::size_t(bond[j]), n);
      joint.on[j] = on ? -1 : 0, any |= on;
      N[0][j] = n[0], N[1][j] = n[1], N[2][j] = n[2];
    }
    if (any) // why: a block without joints runs the unified law alone
    {
      const LaneIndices flip = N[0] * e0[0] + N[1] * e0[1] + N[2] * e0[2] < 0;
      const Lanes sign = flip ? Lanes{} - 1.0 : Lanes{} + 1.0;
      for (int d = 0; d < 3; ++d)
        joint.n0[d] = sign * N[d];
      bond_law_of<dashpots, true>(xa, xb, qa, qb, va, vb, wa, wb, c, f, &joint);
      return;
    }
    bond_law_of<dashpots>(xa, xb, qa, qb, va, vb, wa, wb, c, f);
    for (int d = 0; d < 3; ++d)
      f.n[d] = f.e[d];
  }
  else
    bond_law_of<dashpots>(xa, xb, qa, qb, va, vb, wa, wb, c, f);
}

/// Evaluates bonds k0 .. k0 + m - 1 (m <= W) into @p out: the records always, the rows when
/// @p rows (steps that record forces or test failure). Everything from the gather to the
/// records stays in registers. With `smooth`, the weak-plane and basal bonds are smooth joints
/// (BondLawArrays::joint_of) and the rows hold their failure axes.
template <bool dashpots, bool rows, bool smooth = false>
inline void bond_law_block(const BondLawArrays& in, std::size_t k0, int m, BondBlock& out)
{
  constexpr int W = BondBlock::W;
  constexpr int S = particle_record_size<dashpots>;
  alignas(32) std::int32_t ia[W], ib[W], bond[W];
  // why: a full block's indices are plain vector loads; a clamped index compiles to hardware
  // gathers, which cost ~7 % of a step on these AMD cores when used for every block
  if (m == W)
    for (int j = 0; j < W; ++j)
      ia[j] = in.a[k0 + std::size_t(j)], ib[j] = in.b[k0 + std::size_t(j)], bond[j] = j;
  else
    for (int j = 0; j < W; ++j)
    {
      const int k = std::min(j, m - 1);
      ia[j] = in.a[k0 + std::size_t(k)], ib[j] = in.b[k0 + std::size_t(k)], bond[j] = k;
    }
  Lanes xa[4], xb[4], qa[4], qb[4], e0[4], va[4]{}, vb[4]{}, wa[4]{}, wb[4]{};
  gather_lanes<3>(in.x, ia, xa);
  gather_lanes<3>(in.x, ib, xb);
  gather_lanes<4>(in.q, ia, qa);
  gather_lanes<4>(in.q, ib, qb);
  if constexpr (dashpots)
  {
    gather_lanes<3>(in.v, ia, va);
    gather_lanes<3>(in.v, ib, vb);
    gather_lanes<3>(in.w, ia, wa);
    gather_lanes<3>(in.w, ib, wb);
  }
  gather_lanes<3>(in.e0 + 3 * k0, bond, e0);
  const LawConstants<Lanes> c{load_lanes(in.L0 + k0, m),
                              {e0[0], e0[1], e0[2]},
                              load_lanes(in.kn + k0, m),
                              load_lanes(in.ks + k0, m),
                              load_lanes(in.ktor + k0, m),
                              load_lanes(in.kben + k0, m),
                              load_lanes(in.s + k0, m),
                              dashpots ? load_lanes(in.ct + k0, m) : Lanes{},
                              dashpots ? load_lanes(in.cr + k0, m) : Lanes{}};
  BondForcesOf<Lanes> f;
  block_law<dashpots, smooth>(in, k0, bond, xa, xb, qa, qb, va, vb, wa, wb, e0, c, f);
  Lanes ma[3], mb[3], mda[3]{}, mdb[3]{};
  resultant_moments(f.Fc, f.Mc, f, ma, mb);
  if constexpr (dashpots)
    resultant_moments(f.Fd, f.Md, f, mda, mdb);
  using Ints = std::int32_t __attribute__((vector_size(W * sizeof(std::int32_t))));
  Ints a32, b32;
  __builtin_memcpy(&a32, ia, sizeof a32), __builtin_memcpy(&b32, ib, sizeof b32);
  const auto ends =
      end_lanes<dashpots>(__builtin_convertvector(a32, LaneIndices),
                          __builtin_convertvector(b32, LaneIndices), f, ma, mb, mda, mdb);
  store_records<S>(ends.lower, out.lower);
  store_records<S>(ends.upper, out.upper);
  if constexpr (rows)
  {
    auto put = [](double* row, Lanes v) { __builtin_memcpy(row, &v, sizeof v); };
    for (int d = 0; d < 3; ++d)
    {
      put(out.Fc[d], f.Fc[d]), put(out.Mc[d], f.Mc[d]), put(out.Fd[d], f.Fd[d]);
      put(out.Md[d], f.Md[d]), put(out.e[d], f.e[d]);
    }
    put(out.ra, f.ra), put(out.rb, f.rb), put(out.strain_energy, f.strain_energy);
    if constexpr (smooth)
      for (int d = 0; d < 3; ++d)
        put(out.n[d], f.n[d]);
  }
}
} // namespace dembridge::dem
