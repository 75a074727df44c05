#pragma once
// The unified bond law (bond_kernel.h) on a block of W consecutive bonds at once, in SIMD lanes
// (AVX-512: 8 doubles). The lanes gather their particles' positions, orientations and
// velocities, evaluate the very same bond_law (inlined, so every lane computes bit for bit what
// the scalar kernel computes for its bond, up to the compiler's fused multiply-adds), and leave
// the contact forces in a lane-major block; the caller scatters them to the particles one bond
// at a time (two bonds of a block often share a particle, so the scatter cannot be a vector
// store). Bonds past the end of a range (m < W) repeat the block's first bond and are ignored.
#include "dem/bonds/bond_kernel.h"
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include <algorithm>
#include <cstddef>
#include <vector>

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

/// Contact forces of a block, lane j = bond k0 + j.
struct alignas(64) BondBlock
{
  static constexpr int W = bond_block_width;
  double Fc[3][W], Mc[3][W], Fd[3][W], Md[3][W], e[3][W];
  double ra[W], rb[W], strain_energy[W];

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
  // Gather: the particle data of the block's bonds into lane-major rows (scalar loads: the
  // vectoriser's own gathers, emulated or vgatherdpd, measured slower on this CPU).
  constexpr int n_rows = dashpots ? 26 : 14;
  alignas(64) double g[n_rows][W];
  for (int j = 0; j < W; ++j)
  {
    const std::size_t k = std::size_t(std::min(j, m - 1));
    std::size_t ia = std::size_t(A[k]), ib = std::size_t(B[k]);
    asm("" : "+r"(ia), "+r"(ib)); // keeps this loop scalar (no emulated gathers)
    const double* xa = X + 3 * ia;
    const double* xb = X + 3 * ib;
    const double* qa = Q + 4 * ia;
    const double* qb = Q + 4 * ib;
    for (int d = 0; d < 3; ++d)
      g[d][j] = xa[d], g[3 + d][j] = xb[d];
    for (int d = 0; d < 4; ++d)
      g[6 + d][j] = qa[d], g[10 + d][j] = qb[d];
    if constexpr (dashpots)
    {
      const double* va = V + 3 * ia;
      const double* vb = V + 3 * ib;
      const double* wa = Wv + 3 * ia;
      const double* wb = Wv + 3 * ib;
      for (int d = 0; d < 3; ++d)
        g[14 + d][j] = va[d], g[17 + d][j] = vb[d], g[20 + d][j] = wa[d], g[23 + d][j] = wb[d];
    }
  }
#pragma GCC ivdep
  for (int j = 0; j < W; ++j)
  {
    const int k = std::min(j, m - 1);
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
  }
}
} // namespace dembridge::dem
