#pragma once
// The unified bond law (Chen et al. 2022, Table 8) in a total, co-rotational form.
//
// The seeds integrate force increments dF_c = k v_cr dt (paper eq. 6-7, Table 8). We evaluate
// the same law from the accumulated deformation, measured in a frame that follows the bond
// chord e = (x_b - x_a)/L. This equals the incremental law for small deformation, but it is
// exact under rigid motion of any size (no spurious force after large rotations), needs no
// stored force state, and gives the strain energy in closed form.
//
// Deformation measures (all objective):
//   delta_n = L_0 - L                                     approach of a towards b
//   t_a = q_a e_0, t_b = q_b e_0                          where each particle carries the axis
//   th_a = 2 (e x t_a) / (1 + e.t_a)                      rotation of end a off the chord
//   th_b = 2 (e x t_b) / (1 + e.t_b)                      (tan-half-angle: exact direction,
//                                                          angle to third order)
//   tw   = 2 (vec(q_b q_a^*) . e) / w(q_b q_a^*)          twist of b relative to a
//   delta_s = L (s th_a + (1-s) th_b) x e                 relative transverse displacement
//                                                          of a vs b at the contact point
// Contact-point force and couple on particle b (Table 8, with v_cr dt -> deformation):
//   F_c = k_n delta_n e + k_s delta_s + c_t v_cr
//   M_c = -k_tor tw e + k_ben (th_a - th_b) + c_r w_cr
// with v_cr, w_cr the relative velocities at the contact point (eq. 4-7) feeding the dashpots
// (thesis eq. 35, paper eq. 9-10). Particle resultants (Table 8):
//   F_a -= F_c,  M_a += -M_c + r_ac x (-F_c),   r_ac = s L e
//   F_b += F_c,  M_b +=  M_c + r_bc x F_c,      r_bc = -(1-s) L e
// which conserve linear and angular momentum exactly.
#include "dem/bonds/smooth_joint.h"
#include "dem/core/lanes.h"
#include "dem/core/types.h"
#include <cmath>

namespace dembridge::dem
{
struct BondConstants
{
  double L0;
  Vec3 e0;
  double kn, ks, ktor, kben, s;
  double ct, cr;
};

/// The per-bond constants as the law reads them, for one bond (T = double) or a block's lanes.
template <class T> struct LawConstants
{
  T L0, e0[3], kn, ks, ktor, kben, s, ct, cr;
};

/// Contact force and couple on particle b, their dashpot parts, and the lever arms
/// (r_ac = ra e, r_bc = rb e). The particle resultants follow from these (see bond_resultants).
template <class T> struct BondForcesOf
{
  T Fc[3], Mc[3]; ///< elastic + dashpot
  T Fd[3], Md[3]; ///< dashpot parts (zero without dashpots)
  T e[3];         ///< current bond axis a -> b
  /// The axis the failure check splits the force against: e, or a smooth joint's current
  /// normal (smooth_joint.h). Written by the smooth-joint law and the scalar bond_law only.
  T n[3];
  T ra, rb; ///< signed distances of the contact point from a and b along e
  T strain_energy;
};
using BondForces = BondForcesOf<double>;

/// A smooth joint's input to the law (smooth_joint.h), one bond (T = double) or a block's lanes:
/// the signed formation normal n_0 of eq. (5), and whether the bond (lane) is a joint (-1 / 0
/// lane masks for `mask ? x : y`).
template <class T> struct JointOf
{
  T n0[3];
  bool on;
};
template <> struct JointOf<Lanes>
{
  Lanes n0[3];
  LaneIndices on;
};

inline double lane_select(bool c, double x, double y)
{
  return c ? x : y;
}

inline Lanes lane_select(LaneIndices c, Lanes x, Lanes y)
{
  return c ? x : y;
}

/// The unified law, for one bond (T = double) or for the lanes of a block (T = Lanes): the same
/// source for both, so each lane computes what the scalar kernel computes for its bond (up to
/// the compiler's fused multiply-adds). Written without vector temporaries (about twice as fast
/// as the same expressions in Eigen 3-vectors). Quaternions are read in Eigen's storage order
/// (x, y, z, w). Without dashpots the velocities are not read. With `smooth`, the bonds (lanes)
/// that @p joint marks are smooth joints (smooth_joint.h); without, @p joint is not read and the
/// law is the unified one, instruction for instruction.
template <bool dashpots, bool smooth = false, class T>
[[gnu::always_inline]] inline void bond_law_of(const T* xa, const T* xb, const T* qa, const T* qb,
                                               const T* va, const T* vb, const T* wa, const T* wb,
                                               const LawConstants<T>& c, BondForcesOf<T>& out,
                                               const JointOf<T>* joint = nullptr)
{
  const T dx = xb[0] - xa[0], dy = xb[1] - xa[1], dz = xb[2] - xa[2];
  const T L = lane_sqrt(dx * dx + dy * dy + dz * dz), iL = 1.0 / L;
  const T ex = dx * iL, ey = dy * iL, ez = dz * iL;
  const T e0x = c.e0[0], e0y = c.e0[1], e0z = c.e0[2];
  // t = q e0 (rotate the formation axis with each particle): t = e0 + w u + qv x u, u = 2 qv x e0
  auto rotate = [&](const T* q, T& tx, T& ty, T& tz)
  {
    const T x = q[0], y = q[1], z = q[2], w = q[3];
    const T ux = 2 * (y * e0z - z * e0y), uy = 2 * (z * e0x - x * e0z),
            uz = 2 * (x * e0y - y * e0x);
    tx = e0x + w * ux + (y * uz - z * uy);
    ty = e0y + w * uy + (z * ux - x * uz);
    tz = e0z + w * uz + (x * uy - y * ux);
  };
  T tax, tay, taz, tbx, tby, tbz;
  rotate(qa, tax, tay, taz);
  rotate(qb, tbx, tby, tbz);
  // th = 2 (e x t) / (1 + e.t)
  const T ca = 2.0 / (1.0 + ex * tax + ey * tay + ez * taz);
  const T cb = 2.0 / (1.0 + ex * tbx + ey * tby + ez * tbz);
  const T hax = ca * (ey * taz - ez * tay), hay = ca * (ez * tax - ex * taz),
          haz = ca * (ex * tay - ey * tax);
  const T hbx = cb * (ey * tbz - ez * tby), hby = cb * (ez * tbx - ex * tbz),
          hbz = cb * (ex * tby - ey * tbx);
  // twist: q_r = q_b q_a^*, tw = 2 vec(q_r).e / w(q_r)
  const T rw = qb[3] * qa[3] + qb[0] * qa[0] + qb[1] * qa[1] + qb[2] * qa[2];
  const T rx = qa[3] * qb[0] - qb[3] * qa[0] - (qb[1] * qa[2] - qb[2] * qa[1]);
  const T ry = qa[3] * qb[1] - qb[3] * qa[1] - (qb[2] * qa[0] - qb[0] * qa[2]);
  const T rz = qa[3] * qb[2] - qb[3] * qa[2] - (qb[0] * qa[1] - qb[1] * qa[0]);
  const T tw = 2.0 * (rx * ex + ry * ey + rz * ez) / rw;
  // delta_n, delta_s = L (s th_a + (1-s) th_b) x e, rotation a - b
  const T s = c.s, dn = c.L0 - L;
  const T mx = s * hax + (1 - s) * hbx, my = s * hay + (1 - s) * hby, mz = s * haz + (1 - s) * hbz;
  const T dsx = L * (my * ez - mz * ey), dsy = L * (mz * ex - mx * ez),
          dsz = L * (mx * ey - my * ex);
  const T rotx = hax - hbx, roty = hay - hby, rotz = haz - hbz;
  const T fn = c.kn * dn, mt = -c.ktor * tw;
  out.Fc[0] = fn * ex + c.ks * dsx;
  out.Fc[1] = fn * ey + c.ks * dsy;
  out.Fc[2] = fn * ez + c.ks * dsz;
  out.Mc[0] = mt * ex + c.kben * rotx;
  out.Mc[1] = mt * ey + c.kben * roty;
  out.Mc[2] = mt * ez + c.kben * rotz;
  out.e[0] = ex, out.e[1] = ey, out.e[2] = ez;
  out.ra = s * L;
  out.rb = (s - 1.0) * L;
  out.strain_energy = 0.5 * (c.kn * dn * dn + c.ks * (dsx * dsx + dsy * dsy + dsz * dsz) +
                             c.ktor * tw * tw + c.kben * (rotx * rotx + roty * roty + rotz * rotz));
  if constexpr (smooth)
  {
    // the joint's lanes: eq. (2)-(5) of smooth_joint.h on D = delta_n e + delta_s
    T n[3], F[3], U;
    joint_normal_now(qa, qb, joint->n0, n);
    const T D[3] = {dn * ex + dsx, dn * ey + dsy, dn * ez + dsz};
    smooth_joint_force(D, n, c.kn, c.ks, F, U);
    const T e[3] = {ex, ey, ez};
    for (int d = 0; d < 3; ++d)
    {
      out.Fc[d] = lane_select(joint->on, F[d], out.Fc[d]);
      out.Mc[d] = lane_select(joint->on, T{}, out.Mc[d]);
      out.n[d] = lane_select(joint->on, n[d], e[d]);
    }
    out.strain_energy = lane_select(joint->on, U, out.strain_energy);
  }
  if constexpr (dashpots)
  {
    // v_cr = (v_a + w_a x r_ac) - (v_b + w_b x r_bc) (eq. 6), w_cr = w_a - w_b (eq. 7)
    const T ra = out.ra, rb = out.rb;
    const T vx = va[0] + ra * (wa[1] * ez - wa[2] * ey) - vb[0] - rb * (wb[1] * ez - wb[2] * ey);
    const T vy = va[1] + ra * (wa[2] * ex - wa[0] * ez) - vb[1] - rb * (wb[2] * ex - wb[0] * ez);
    const T vz = va[2] + ra * (wa[0] * ey - wa[1] * ex) - vb[2] - rb * (wb[0] * ey - wb[1] * ex);
    out.Fd[0] = c.ct * vx, out.Fd[1] = c.ct * vy, out.Fd[2] = c.ct * vz;
    out.Md[0] = c.cr * (wa[0] - wb[0]);
    out.Md[1] = c.cr * (wa[1] - wb[1]);
    out.Md[2] = c.cr * (wa[2] - wb[2]);
    out.Fc[0] += out.Fd[0], out.Fc[1] += out.Fd[1], out.Fc[2] += out.Fd[2];
    out.Mc[0] += out.Md[0], out.Mc[1] += out.Md[1], out.Mc[2] += out.Md[2];
  }
  else
  {
    out.Fd[0] = out.Fd[1] = out.Fd[2] = T{};
    out.Md[0] = out.Md[1] = out.Md[2] = T{};
  }
}

/// The unified law for one bond: the scalar kernel (tests, tools, the per-bond measurements).
/// With @p joint_normal (N, unit), the bond is a smooth joint across the plane of normal N
/// (smooth_joint.h).
template <bool dashpots>
[[gnu::always_inline]] inline void
bond_law(const double* xa, const double* xb, const double* qa, const double* qb, const double* va,
         const double* vb, const double* wa, const double* wb, const BondConstants& c,
         BondForces& out, const Vec3* joint_normal = nullptr)
{
  const LawConstants<double> k{
      c.L0, {c.e0[0], c.e0[1], c.e0[2]}, c.kn, c.ks, c.ktor, c.kben, c.s, c.ct, c.cr};
  if (joint_normal)
  {
    const double sign = joint_normal->dot(c.e0) < 0 ? -1.0 : 1.0; // eq. (5)
    const JointOf<double> j{
        {sign * joint_normal->x(), sign * joint_normal->y(), sign * joint_normal->z()}, true};
    bond_law_of<dashpots, true>(xa, xb, qa, qb, va, vb, wa, wb, k, out, &j);
    return;
  }
  bond_law_of<dashpots>(xa, xb, qa, qb, va, vb, wa, wb, k, out);
  out.n[0] = out.e[0], out.n[1] = out.e[1], out.n[2] = out.e[2];
}

/// The particle resultants' moments (Table 8) of a contact force F and couple M acting on b at
/// the contact point: M_a = -M - r_a e x F on a, M_b = M + r_b e x F on b (the forces are -F on
/// a and F on b).
template <class T>
[[gnu::always_inline]] inline void resultant_moments(const T* F, const T* M,
                                                     const BondForcesOf<T>& f, T* Ma, T* Mb)
{
  const T cx = f.e[1] * F[2] - f.e[2] * F[1], cy = f.e[2] * F[0] - f.e[0] * F[2],
          cz = f.e[0] * F[1] - f.e[1] * F[0];
  Ma[0] = -M[0] - f.ra * cx, Ma[1] = -M[1] - f.ra * cy, Ma[2] = -M[2] - f.ra * cz;
  Mb[0] = M[0] + f.rb * cx, Mb[1] = M[1] + f.rb * cy, Mb[2] = M[2] + f.rb * cz;
}

/// Particle resultants (Table 8) of a contact force F and couple M acting on b at the contact
/// point, added to a's and b's: F_a = -F, M_a = -M - r_a e x F;  F_b = F, M_b = M + r_b e x F.
inline void bond_resultants(const double* F, const double* M, const BondForces& f, double* Fa,
                            double* Ma, double* Fb, double* Mb)
{
  double ma[3], mb[3];
  resultant_moments(F, M, f, ma, mb);
  for (int d = 0; d < 3; ++d)
    Fa[d] -= F[d], Fb[d] += F[d], Ma[d] += ma[d], Mb[d] += mb[d];
}

/// Eigen-typed view of one bond, for tests and tools (same code path as the solver).
struct BondKinematics
{
  Vec3 xa, xb;
  Quat qa, qb;
  Vec3 va, vb, wa, wb;
};

struct BondResult
{
  Vec3 Fc, Mc;          ///< contact force/couple on b (elastic + dashpot)
  Vec3 Fa, Ma, Fb, Mb;  ///< particle resultants
  double strain_energy; ///< elastic energy stored in the bond, J
};

/// With @p joint_normal: a smooth joint (smooth_joint.h).
template <bool dashpots = true>
inline BondResult evaluate_bond(const BondKinematics& k, const BondConstants& c,
                                const Vec3* joint_normal = nullptr)
{
  BondForces f;
  bond_law<dashpots>(k.xa.data(), k.xb.data(), k.qa.coeffs().data(), k.qb.coeffs().data(),
                     k.va.data(), k.vb.data(), k.wa.data(), k.wb.data(), c, f, joint_normal);
  BondResult r;
  r.Fc = Vec3(f.Fc[0], f.Fc[1], f.Fc[2]);
  r.Mc = Vec3(f.Mc[0], f.Mc[1], f.Mc[2]);
  r.Fa = r.Ma = r.Fb = r.Mb = Vec3::Zero();
  bond_resultants(f.Fc, f.Mc, f, r.Fa.data(), r.Ma.data(), r.Fb.data(), r.Mb.data());
  r.strain_energy = f.strain_energy;
  return r;
}
} // namespace dembridge::dem
