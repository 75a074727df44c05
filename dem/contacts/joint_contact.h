#pragma once
// The unbonded smooth joint: two spheres on the two sides of a joint plane, their bond across it
// broken or never formed, meet on the plane, not as spheres (Mas Ivars et al. 2011, Int. J. Rock
// Mech. Min. Sci. 48, 219-244, section 2: PFC's smooth joint once unbonded; Scholtes & Donze
// 2012, Int. J. Rock Mech. Min. Sci. 52, 18-30, YADE's JCFpm, whose joint interactions keep the
// joint's normal after their bond breaks and between any two particles on the joint's sides):
//   n   = +-N, from i's side of the plane to j's (bonds/sliding_joints.h)               (1)
//   u_n = (X_j - X_i) . n - (x_j - x_i) . n     approach across the plane since the
//                                               reference positions X                   (2)
//   F_n = F_el(u_n) for u_n > 0, else 0, no tension                                     (3)
//   v_t = (v_j - v_i) - ((v_j - v_i) . n) n     sliding velocity in the plane            (4)
//   xi += v_t dt,   |k_t xi| <= mu_j F_n        shear spring with Coulomb's cap, slip beyond
//                                               (tangential_spring.h)                    (5)
//   F   = F_n n - k_t xi on j, -F on i, at the centres (no couple, as JCFpm)             (6)
//   U   = U_n(u_n) + k_t |xi|^2 / 2                                                      (7)
// The springs: a broken bond's pair keeps its bond's k_n and k_s (F_el = k_n u_n, k_t = k_s),
// as PFC's smooth joint keeps its stiffnesses when its bond breaks, so the normal force goes on
// without a jump; a pair that never had a bond takes the contact law's (linear: k_n u_n, k_t;
// Hertz: 4/3 E* sqrt(R*) u_n^1.5 and its k_t). A broken bond's pair also takes over its bond's
// shear when it first touches after the break (PFC keeps the shear force, capped): its spring
// starts at the pair's in-plane displacement since the reference positions, capped,
//   xi_0 = d_t min(1, mu_j F_n / (k_t |d_t|)),
//   d_t  = d - (d . n) n,  d = (x_j - x_i) - (X_j - X_i)                                (8)
// (the centres' part of the bond's shear; the particles' rotations the joint does not see).
// A new pair without a bond starts at xi = 0.
// So the pair slides along the plane, resisting with mu_j F_n only, and never rides up over its
// partner as two spheres would (no interlocking across the joint). The pair acts while its
// spheres are within reach (|x_j - x_i| below R_i + R_j, or the bond's rest length for a broken
// bond's pair) and u_n > 0. Energy: the forces' power on the particles, F . (v_j - v_i), is
// exactly -dU/dt less the slip's dissipation, as for the contacts (contact_kernel.h); a pair
// that comes within reach with u_n > 0 starts with the energy U of eq. (7) (a broken bond's
// pair at its first step takes it from the fracture energy, as a contact that a broken bond
// hands over, contact_forces.h). The couple x_j - x_i times F that forces at the centres leave
// is not balanced (JCFpm's choice: the particles of a joint are not turned by it).
#include "dem/contacts/tangential_spring.h"
#include "dem/core/types.h"

namespace dembridge::dem
{
/// What one unbonded joint pair gives: the force on j (on i: -force), the normal force F_n, the
/// stored energy U, the slip's dissipation over the step, and the rate at which the springs
/// store energy (as ContactOutput).
struct JointContactOutput
{
  Vec3 force;
  double normal_force, energy, slip, power;
};

/// Eq. (3)-(7) for the approach @p u_n (> 0) along @p n and the relative velocity
/// @p v_rel = v_j - v_i, with the springs of @p law (a contact law, or a broken bond's as a
/// LinearSpringDashpot; its elastic parts only: a joint has no dashpot), friction @p mu_j and
/// the history (xi, k_t: 0 for a new pair).
template <class Law>
inline JointContactOutput joint_contact_force(const Law& law, const Vec3& n, double u_n,
                                              const Vec3& v_rel, double r_eff, double m_eff,
                                              double mu_j, double dt, Vec3& xi, double& kt)
{
  const auto r = law(u_n, r_eff, m_eff);
  const double v_n = v_rel.dot(n);
  const Vec3 v_t = v_rel - v_n * n;
  JointContactOutput out;
  out.normal_force = r.force; // eq. (3)
  xi -= xi.dot(n) * n;        // the spring lies in the plane
  out.slip = follow_stiffness(xi, kt, r.kt);
  kt = r.kt;
  out.slip += plastic_spring_step(xi, v_t * dt, r.kt, mu_j * r.force); // eq. (5)
  out.force = r.force * n - r.kt * xi;                                 // eq. (6)
  out.energy = r.energy + 0.5 * r.kt * xi.squaredNorm();               // eq. (7)
  out.power = -r.force * v_n + r.kt * xi.dot(v_t);
  return out;
}

/// Eq. (8): the starting shear spring of a broken bond's pair whose normal force is @p f_n.
inline Vec3 joint_shear_handover(const Vec3& n, const Vec3& x_i, const Vec3& x_j, const Vec3& X_i,
                                 const Vec3& X_j, double kt, double mu_j, double f_n)
{
  const Vec3 d = (x_j - x_i) - (X_j - X_i);
  const Vec3 d_t = d - d.dot(n) * n;
  const double force = kt * d_t.norm(), cap = mu_j * f_n;
  return force > cap ? Vec3(d_t * (cap / force)) : d_t;
}

/// Eq. (2): the approach across the plane of normal @p n since the reference positions.
inline double joint_approach(const Vec3& n, const Vec3& x_i, const Vec3& x_j, const Vec3& X_i,
                             const Vec3& X_j)
{
  return n.dot((X_j - X_i) - (x_j - x_i));
}
} // namespace dembridge::dem
