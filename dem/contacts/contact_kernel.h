#pragma once
// One contact between body i and sphere j (i: a sphere or a rigid wall), any law (template):
//   n      unit normal from i to j;  delta = R_i + R_j - |x_j - x_i| > 0 the overlap (sphere-wall:
//          R_j - gap);  contact point x_c = x_i + a_i n = x_j - a_j n, a = R - delta/2 (thesis
//          Fig. 17-18)
//   v_rel  = (v_j + w_j x (-a_j n)) - (v_i + w_i x (a_i n))   velocity of j relative to i at x_c
//          (thesis eq. 14 with the roles of A and B swapped);  v_n = v_rel . n,  v_t the rest
//   F_n    = F_el(delta) - c_n v_n             (law; d(delta)/dt = -v_n)
//   xi    += v_t dt  (carried into the current plane and to the current k_t first,
//            tangential_spring.h),  F_t = -k_t xi - c_t v_t,
//            |k_t xi| <= mu max(F_n, 0): beyond it the spring slips and the dashpot is idle
//   M_r    on i: -k_r theta_r,  theta_r += (w_i - w_j)_t dt,  |k_r theta_r| <= mu_r R* F_n
//   force on j: F = F_n n + F_t; on i: -F.  Torques: on j (-a_j n) x F - M_r, on i (a_i n) x (-F)
//   + M_r.  The power of the contact on the two bodies is then exactly F . v_rel + M_r . (w_i -
//   w_j), which the energy terms below split into stored, slip and dashpot parts.
// The dashpot acts with the velocities of the half step before (v^{n-1/2}), as the bond
// dashpots do (explicit_solver.h).
#include "dem/contacts/rolling_resistance.h"
#include "dem/contacts/tangential_spring.h"

namespace dembridge::dem
{
struct ContactInput
{
  Vec3 n;       ///< unit normal i -> j
  double delta; ///< overlap > 0, m
  double arm_i; ///< |x_c - x_i| (0 for a wall), m
  double arm_j; ///< |x_c - x_j|, m
  Vec3 vi, wi, vj, wj;
  double spin;  ///< rate (rad/s) at which the contact plane turns about n: the pair's mean spin
  double r_eff; ///< R*, m
  double m_eff; ///< m*, kg
};

struct ContactOutput
{
  Vec3 force; ///< on j (on i: -force), N
  Vec3 torque_i, torque_j;
  Vec3 damping_force;  ///< the dashpot part of force (on j), N
  double normal_force; ///< F_n (elastic + dashpot), N
  double energy;       ///< stored: normal + tangential + rolling springs, J
  double slip;         ///< energy dissipated by Coulomb slip and rolling plasticity this step, J
  double damping;      ///< dissipation rate of the dashpots, -F_d . v_rel >= 0, W
  double power;        ///< rate at which the springs store energy, W (at v^{n-1/2})
};

/// The history of one contact (kept beside the neighbour list): the tangential spring xi (m),
/// the rolling spring theta (rad) and the stiffnesses they had at the last step (0: new).
struct ContactHistory
{
  Vec3& xi;
  Vec3& theta;
  double& kt;
  double& kr;
};

template <class Law, bool rolling>
inline ContactOutput contact_force(const Law& law, const ContactInput& c, double mu,
                                   const RollingResistance& roll, double dt, ContactHistory h)
{
  const Vec3& n = c.n;
  const Vec3 v_rel = (c.vj - c.arm_j * c.wj.cross(n)) - (c.vi + c.arm_i * c.wi.cross(n));
  const double v_n = v_rel.dot(n);
  const Vec3 v_t = v_rel - v_n * n;
  const auto r = law(c.delta, c.r_eff, c.m_eff);
  ContactOutput out;
  out.normal_force = r.force - r.cn * v_n; // eq. (12) with the dashpot

  // Tangential spring with Coulomb's cap (eq. 13)
  Vec3& xi = h.xi;
  xi = carry_into_plane(xi, n, c.spin * dt);
  out.slip = follow_stiffness(xi, h.kt, r.kt);
  h.kt = r.kt;
  const double cap = mu * (out.normal_force > 0 ? out.normal_force : 0.0);
  const double sliding = plastic_spring_step(xi, v_t * dt, r.kt, cap);
  out.slip += sliding;
  const Vec3 damping_t = sliding > 0 ? Vec3(Vec3::Zero()) : Vec3(-r.ct * v_t);
  out.damping_force = damping_t - r.cn * v_n * n;
  out.force = out.normal_force * n - r.kt * xi + damping_t;
  out.damping = -out.damping_force.dot(v_rel);
  out.energy = r.energy + 0.5 * r.kt * xi.squaredNorm();
  out.power = -r.force * v_n + r.kt * xi.dot(v_t);

  const Vec3 arm_force = n.cross(out.force);
  out.torque_i = -c.arm_i * arm_force;
  out.torque_j = -c.arm_j * arm_force;
  if constexpr (rolling)
  {
    Vec3 w_rel = c.wi - c.wj;
    w_rel -= w_rel.dot(n) * n;
    Vec3& theta = h.theta;
    theta = carry_into_plane(theta, n, c.spin * dt);
    const double kr = roll.spring(r.stiffness, c.r_eff);
    out.slip += follow_stiffness(theta, h.kr, kr);
    h.kr = kr;
    out.slip += plastic_spring_step(theta, w_rel * dt, kr, roll.limit(out.normal_force, c.r_eff));
    const Vec3 moment = -kr * theta; // on i
    out.torque_i += moment;
    out.torque_j -= moment;
    out.energy += 0.5 * kr * theta.squaredNorm();
    out.power += kr * theta.dot(w_rel);
  }
  return out;
}
} // namespace dembridge::dem
