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
#include "types.h"

namespace dembridge::dem
{
/// Per-bond inputs, gathered from the stores.
struct BondKinematics
{
  Vec3 xa, xb;
  Quat qa, qb;
  Vec3 va, vb, wa, wb;
};

struct BondConstants
{
  double L0;
  Vec3 e0;
  double kn, ks, ktor, kben, s;
  double ct, cr;
};

struct BondResult
{
  Vec3 Fc, Mc;       ///< contact force/couple on b (elastic + dashpot)
  Vec3 Fd, Md;       ///< their dashpot parts
  Vec3 Fa, Ma, Fb, Mb; ///< particle resultants
  double strain_energy; ///< elastic energy stored in the bond, J
  Vec3 rac, rbc;         ///< contact point from the particle centres
};

/// Evaluates one bond. Inline: this is the hot loop body. Without dashpots the velocities are
/// not read.
template <bool dashpots = true>
inline BondResult evaluate_bond(const BondKinematics& k, const BondConstants& c)
{
  BondResult r;
  const Vec3 d = k.xb - k.xa;
  const double L = d.norm();
  const Vec3 e = d / L;
  const Vec3 ta = k.qa * c.e0;
  const Vec3 tb = k.qb * c.e0;
  const Vec3 tha = (2.0 / (1.0 + e.dot(ta))) * e.cross(ta);
  const Vec3 thb = (2.0 / (1.0 + e.dot(tb))) * e.cross(tb);
  const Quat qr = k.qb * k.qa.conjugate();
  const double tw = 2.0 * qr.vec().dot(e) / qr.w();
  const double dn = c.L0 - L;
  const Vec3 ds = L * (c.s * tha + (1.0 - c.s) * thb).cross(e);
  const Vec3 dth = tha - thb;

  const Vec3 rac = (c.s * L) * e;
  const Vec3 rbc = ((c.s - 1.0) * L) * e;
  r.Fc = (c.kn * dn) * e + c.ks * ds;
  r.Mc = (-c.ktor * tw) * e + c.kben * dth;
  if constexpr (dashpots)
  {
    const Vec3 vcr = (k.va + k.wa.cross(rac)) - (k.vb + k.wb.cross(rbc)); // eq. 6
    const Vec3 wcr = k.wa - k.wb;                                         // eq. 7
    r.Fd = c.ct * vcr;
    r.Md = c.cr * wcr;
    r.Fc += r.Fd;
    r.Mc += r.Md;
  }
  r.rac = rac;
  r.rbc = rbc;
  r.Fa = -r.Fc;
  r.Fb = r.Fc;
  r.Ma = -r.Mc + rac.cross(r.Fa);
  r.Mb = r.Mc + rbc.cross(r.Fb);
  r.strain_energy = 0.5 * (c.kn * dn * dn + c.ks * ds.squaredNorm() + c.ktor * tw * tw +
                           c.kben * dth.squaredNorm());
  return r;
}
} // namespace dembridge::dem
