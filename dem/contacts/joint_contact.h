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
// The hand-over takes no more than the bond held: the pair's approach since the reference
// positions can exceed the bond's own compression (the bond's normal turns with its particles,
// eq. 5 of smooth_joint.h, the plane's does not), so the joint's springs start from
//   u_0 = u_n - min(u_n, sqrt(2 U_b / (k_n (1 + mu_j^2 k_n / k_t)))),   u_n <- u_n - u_0  (8b)
// U_b the energy the bond's failure booked, with 0.5 k_n u_n^2 + 0.5 k_t |xi_0|^2 <= U_b
// (|xi_0| <= mu_j k_n u_n / k_t); the pair keeps u_0 while it stays listed. Any other pair
// starts from u_0 = 0.
// A new pair without a bond starts at xi = 0.
// So the pair slides along the plane, resisting with mu_j F_n only, and never rides up over its
// partner as two spheres would (no interlocking across the joint). The pair acts while its
// spheres are within reach (|x_j - x_i| below R_i + R_j, or the bond's rest length for a broken
// bond's pair) and u_n > 0. Energy: the forces' power on the particles, F . (v_j - v_i), is
// exactly -dU/dt less the slip's dissipation, as for the contacts (contact_kernel.h). Unlike a
// sphere contact, whose U falls to 0 as it opens, a joint pair's U jumps where it comes within
// reach, or leaves it, while the plane is compressed (u_n > 0 there): the plane's load passes
// from pair to pair as the sides slide. Each jump is booked, in the solver's time-centred form
// (the force acting from step n on, or up to step n-1, over half a step):
//   arriving at t_n:  U^n - dt/2 dU/dt^n                                                  (9)
//   leaving at t_n:   U^{n-1} - dt/2 F^{n-1} . (v_j - v_i)^{n-1/2},                      (10)
//                     from the last step's state x^{n-1} = x^n - dt v^{n-1/2}
// A broken bond's pair at its first step after the break takes (9) from the fracture energy
// (the solver booked the bond's whole strain energy there, as for a contact that a broken bond
// hands over, contact_forces.h), once: the hand-over of eq. (8) happens only then, and a pair
// that opens later starts again at xi = 0, as a new pair does. Every other arrival (9) is
// booked against, and every departure (10) into, the friction term: in steady sliding the
// normal springs arriving and leaving balance on average, and the shear springs, loaded to
// mu_j F_n, are released, so the joint dissipates mu_j F_n per unit slip, as a rough plane
// does. The couple x_j - x_i times F that forces at the centres leave
// is not balanced (JCFpm's choice: the particles of a joint are not turned by it).
#include "dem/contacts/tangential_spring.h"
#include "dem/core/types.h"
#include <algorithm>
#include <cmath>

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

/// Eq. (10): the energy a pair leaving reach at t_n held, from its springs after the last step
/// (xi, k_t), its approach @p u_before at t_{n-1} and the relative velocity v^{n-1/2}.
template <class Law>
inline double joint_release(const Law& law, const Vec3& n, double u_before, const Vec3& v_rel,
                            double r_eff, double m_eff, double dt, const Vec3& xi, double kt)
{
  const auto r = law(std::max(u_before, 0.0), r_eff, m_eff);
  const Vec3 force = r.force * n - kt * xi;
  const double energy = r.energy + 0.5 * kt * xi.squaredNorm();
  return energy - 0.5 * dt * force.dot(v_rel);
}

/// Eq. (8b): the approach a broken bond's pair starts from, its approach @p u_n since the
/// reference positions capped so that the joint's springs (k_n, k_s, the shear at its cap)
/// hold no more than the energy @p released that the bond's failure booked.
inline double joint_start_approach(double u_n, double released, double kn, double ks, double mu_j)
{
  const double cap =
      std::sqrt(2.0 * std::max(released, 0.0) / (kn * (1.0 + mu_j * mu_j * kn / ks)));
  return std::min(u_n, cap);
}

/// Eq. (2): the approach across the plane of normal @p n since the reference positions.
inline double joint_approach(const Vec3& n, const Vec3& x_i, const Vec3& x_j, const Vec3& X_i,
                             const Vec3& X_j)
{
  return n.dot((X_j - X_i) - (x_j - x_i));
}
} // namespace dembridge::dem
