#pragma once
// Rolling resistance, elastic-plastic spring (Ai, Chen, Rotter & Ooi 2011, Powder Technology
// 206:269-282, model C, the elastic-plastic spring-dashpot "EPSD", without its optional dashpot;
// LIGGGHTS' rolling_friction epsd):
//   d(theta_r) = omega_r dt,  omega_r = (omega_i - omega_j) projected on the contact plane
//   M_r = -k_r theta_r  (on particle i; -M_r on j),  |M_r| <= M_r^m = mu_r R* F_n  (full
//   mobilisation) k_r = 2.25 k_n mu_r^2 R*^2   (k_n the normal contact stiffness; Ai et al.'s 3D
//   prefactor)
// A sphere of radius R rolling on a plane under gravity loses its kinetic energy 7/10 m v0^2 to
// the plastic moment mu_r R m g over the rolled angle s/R, so it stops after
//   s = 7 v0^2 / (10 mu_r g).
// Stored energy 1/2 k_r |theta_r|^2; the slip part dissipates (tangential_spring.h).
// Units: k_r N·m/rad, theta rad, M N·m.

namespace dembridge::dem
{
struct RollingResistance
{
  double friction = 0;  ///< mu_r (dimensionless)
  double stiffness = 0; ///< k_r, N·m/rad; 0: 2.25 k_n mu_r^2 R*^2 (Ai et al.)

  double spring(double normal_stiffness, double r_eff) const
  {
    return stiffness > 0 ? stiffness
                         : 2.25 * normal_stiffness * friction * friction * r_eff * r_eff; // k_r
  }
  double limit(double normal_force, double r_eff) const
  {
    return friction * r_eff * (normal_force > 0 ? normal_force : 0.0); // M_r^m
  }
};
} // namespace dembridge::dem
