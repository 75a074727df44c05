#pragma once
// Critical time step of the central-difference (position Verlet) scheme, dt_crit = 2/omega_max
// (thesis eq. 46), estimated two ways:
//  - thesis eq. 48 (O'Sullivan & Bray): dt <= 0.22 sqrt(m_p / k_n), smallest over bonds;
//    translations only, for equal normal and shear springs in a close packing;
//  - a rigorous per-bond bound covering rotations: by the element eigenvalue inequality
//    lambda_max(M^-1 K) <= max_e lambda_max(M_e^-1 K_e) when each particle's mass and inertia are
//    shared among its C bonds (M_e = diag(m_a/C_a, I_a/C_a, m_b/C_b, I_b/C_b)), with K_e the
//    linearised unified-law matrix of the bond (bond_matrix.h).
// Viscous dashpots (force from v^{n-1/2}) lower it: with mu the largest eigenvalue of
// M_e^-1 C_e (C_e: the bond law with the dashpot coefficients as stiffnesses), the 1-DOF
// condition omega^2 dt^2 + 2 mu dt <= 4 gives dt = (sqrt(mu^2 + 4 omega^2) - mu) / omega^2
// (= 2/omega (sqrt(1 + zeta^2) - zeta) for one mode). Particle ("local")
// damping, F - gamma |F| sign(v), amplifies the force by up to (1 + gamma) when the force
// opposes the motion, so it lowers the limit by 1/sqrt(1 + gamma).
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include <algorithm>
#include <limits>

namespace dembridge::dem
{
struct TimeStepEstimate
{
  double thesis_eq48 = 0; ///< s, 0.22 sqrt(m/k) (translations only)
  double bond_bound = 0;  ///< s, element eigenvalue bound incl. rotations and damping
  /// s, contacts and walls (ContactForces::critical_time_step); infinity without contacts
  double contact_bound = std::numeric_limits<double>::infinity();
  double critical() const { return std::min(bond_bound, contact_bound); }
};

TimeStepEstimate estimate_critical_time_step(const ParticleStore& p, const BondStore& bonds,
                                             double particle_damping = 0);
} // namespace dembridge::dem
