#pragma once
// Bond stiffness as 12x12 matrices in the bond's local frame (x along a -> b), DOF order
// [u_a, theta_a, u_b, theta_b]. Two independent constructions:
//  - unified_bond_matrix: the linearised unified law, K = B^T D B with B mapping DOFs to
//    (delta_n, delta_s, rotation a-b) at the contact point and D = diag(kn, ks, ks, ktor, kben,
//    kben);
//  - timoshenko_beam_matrix: the thesis' closed-form Timoshenko beam matrix (eq. 26-31,
//    Przemieniecki), built from E_b, nu_b, r_b, L_b alone.
// For the TBBM the two agree (tests/dem), which checks the unified kernel against the thesis.
// Both are also what the static solver and the per-bond time-step bound use.
#include "dem/bonds/bond_model.h"
#include <Eigen/Dense>

namespace dembridge::dem
{
using Matrix12 = Eigen::Matrix<double, 12, 12>;
using Vector12 = Eigen::Matrix<double, 12, 1>;

/// Linearised unified law (forces on the particles = -K u).
Matrix12 unified_bond_matrix(const BondStiffness& k, double length);

/// Linearised smooth joint (smooth_joint.h eq. 2-3): the unified law's B with
/// D = [k_n n n^T + k_s (I - n n^T), 0; 0, 0], n the joint's normal in the bond's local frame.
Matrix12 smooth_joint_matrix(const BondStiffness& k, double length, const Vec3& local_normal);

/// The bond matrix of bond-like constants @p k: a smooth joint's with @p local_normal, else the
/// unified law's.
inline Matrix12 bond_matrix(const BondStiffness& k, double length, const Vec3* local_normal)
{
  return local_normal ? smooth_joint_matrix(k, length, *local_normal)
                      : unified_bond_matrix(k, length);
}

/// Thesis eq. 26-31.
Matrix12 timoshenko_beam_matrix(double youngs_modulus, double poisson_ratio, double bond_radius,
                                double length);

/// Rotation taking local (x along axis) components to global components: columns are the local
/// axes; y is e x z_global normalised (thesis eq. 6-8), or global y if e is along z (eq. 7).
Eigen::Matrix3d bond_frame(const Vec3& axis);
} // namespace dembridge::dem
