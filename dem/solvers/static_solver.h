#pragma once
// Quasi-static (linear static) solver for bonded-particle networks: the equilibrium the explicit
// solver settles to, found in one sparse solve instead of many damped time steps.
//
// Unknowns: 6 DOFs per particle, u_i = [u_x, u_y, u_z, theta_x, theta_y, theta_z] (DofBit order),
// displacements and small rotations from the reference configuration (bond formation).
// Every intact bond contributes its linearised stiffness in global coordinates
//   K_g = T K_l T^T,   T = diag(R, R, R, R),   R = bond_frame(e_0)        (thesis eq. 6-8, 32)
// where K_l is the 12x12 unified bond matrix in the bond frame, DOF order [u_a, th_a, u_b, th_b]
// (bond_matrix.h; for the TBBM it is the thesis' Timoshenko beam matrix, eq. 23-31; for every
// model its stiffnesses and contact point are those of paper Tables 8-9). Forces on the particles
// are -K u, so equilibrium with the external loads f is
//   K u = f.
// Supports (Constraint masks) fix DOFs at zero; prescribed motion (velocity / angular velocity
// loads) fixes DOFs at a given displacement g. With the DOFs split into free (f) and fixed (c):
//   K_ff u_f = f_f - K_fc g_c,   reactions r_c = (K u)_c - f_c.
// K_ff is solved after symmetric Jacobi scaling (S K_ff S, S = diag(K_ii)^-1/2, which makes the
// pivots unit-free across N/m and N·m/rad DOFs) by a sparse LDL^T factorisation (Eigen
// SimplicialLDLT) or, above a size limit, by conjugate gradients (Jacobi, i.e. the scaling itself,
// or incomplete Cholesky as preconditioner).
//
// The result matches the explicit solver's quasi-static end state to first order in the
// deformation (the explicit bond law is co-rotational, bond_kernel.h; the two agree while
// rotations and strains are small).
#include "dem/model/model.h"
#include <Eigen/SparseCore>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace dembridge::dem
{
/// The scaled free system A y = b that the static solver hands to a pluggable iterative solver
/// (StaticSettings::iterative_solver): A = S K_ff S (unit diagonal), b = S (f_f - K_fc g_c),
/// u_f = S y. Layers above dem/ plug in solvers dem/ cannot depend on (PETSc's GAMG,
/// fem/bond_network_solver.h); what they need to build a near-null space comes with it.
struct StaticLinearSystem
{
  const Eigen::SparseMatrix<double>& matrix; ///< A, lower triangle, column-major
  const Eigen::VectorXd& rhs;                ///< b
  /// 6 per particle (DofBit order): the unknown of DOF 6 i + k, or -1 where it is held
  const std::vector<int>& free_index;
  const Eigen::VectorXd& scale;       ///< S: u of unknown r = scale[r] * y[r]
  const std::vector<Vec3>& positions; ///< reference centres (rigid-body rotations)
  double tolerance = 1e-10;           ///< stop at |b - A y| <= tolerance |b|
};

struct StaticLinearSolution
{
  Eigen::VectorXd y;
  bool converged = false;
  long iterations = 0;
  double setup_seconds = 0; ///< preconditioner set-up, part of the solve time
  std::string method;       ///< e.g. "PETSc CG+GAMG"
};

struct StaticSettings
{
  enum class Method
  {
    automatic,             ///< direct for small or banded systems, else cg_jacobi (LDLT if
                           ///< that does not converge)
    direct,                ///< SimplicialLDLT (exact; detects any free rigid-body mode)
    cg_jacobi,             ///< conjugate gradients, Jacobi preconditioner
    cg_incomplete_cholesky ///< conjugate gradients, incomplete Cholesky preconditioner
  } method = Method::automatic;
  /// automatic: direct up to this many free DOFs. Measured on HCP blocks (2-core machine,
  /// loaded): LDLT 0.11 s vs Jacobi CG 0.011 s at 864 DOFs, 1.0 s vs 0.055 s at 4.6k, 17 s vs
  /// 0.95 s at 19k, LDLT not done in 17 min vs CG 15 s at 155k: Eigen's simplicial LDL^T fills
  /// in badly on 3-D networks.
  long direct_limit = 300;
  /// automatic: also direct when the mean particle index distance across bonds is at most
  /// this (chains, beams: banded, O(n) to factor, slow for CG).
  double banded_gap = 4;
  double cg_tolerance = 1e-10; ///< relative residual of the scaled system
  /// When set, solves the scaled free system in place of Eigen's Jacobi CG (Method::automatic
  /// above the direct limit, Method::cg_jacobi), to cg_tolerance; if it does not converge,
  /// automatic falls back to the factorisation as it does for CG.
  std::function<StaticLinearSolution(const StaticLinearSystem&)> iterative_solver;
  /// iterative_solver only from this many free unknowns (below it, Jacobi CG). An AMG's set-up
  /// costs what a few hundred CG iterations do: measured on the thesis compression test, GAMG
  /// and Jacobi CG take the same time at 26 k HCP particles (156 k unknowns), GAMG wins above.
  long iterative_solver_min_unknowns = 0;
  /// Time (s) at which the loads are taken. Infinite (default): the final state, i.e. force and
  /// moment loads at their full value, loads with a finite end_time left out (the explicit run
  /// ends with them removed), and velocity / angular velocity loads read as prescribed
  /// displacements / rotations equal to `value` (m, rad) on their components. Finite: every
  /// load as the explicit solver has it at that time (ramp factor, end_time), a prescribed
  /// motion as the displacement its ramped velocity has accumulated by then.
  double time = std::numeric_limits<double>::infinity();

  /// Per-particle prescribed displacements beside the model's supports and loads, for fields a
  /// group-wide load cannot describe (the affine boundary field of elasticity_tensor.h): the DOFs
  /// in `dofs` (DofBit mask) of particle `index` held at `value` = [u_x, u_y, u_z, theta_x,
  /// theta_y, theta_z] (m, rad). Applied after the loads, so they win on a shared DOF.
  struct PrescribedDisplacement
  {
    int index = 0;
    std::uint8_t dofs = 0;
    Eigen::Matrix<double, 6, 1> value = Eigen::Matrix<double, 6, 1>::Zero();
  };
  std::vector<PrescribedDisplacement> prescribed;
};

struct StaticResult
{
  long n_dofs = 0;      ///< 6 per particle
  long n_free_dofs = 0; ///< unknowns of the solve
  double assembly_seconds = 0;
  double solve_seconds = 0; ///< factorisation (or preconditioner) + solve
  double residual = 0;      ///< |(K u - f)_free| / |f_f - K_fc g_c|
  std::string method;  ///< "SimplicialLDLT", "ConjugateGradient+Jacobi" or "...+IncompleteCholesky"
  long iterations = 0; ///< CG iterations (0 for the direct solve)
  double setup_seconds = 0; ///< preconditioner set-up of a plugged-in solver (in solve_seconds)
  long held_unbonded =
      0; ///< supported spheres without any bond, held where their supports put them
};

/// Solves K u = f for the model's reference configuration and writes the equilibrium into
/// model.particles: position = reference + u, orientation = exp(theta), velocities zero, and in
/// force / torque the support reactions on constrained DOFs (the explicit solver's convention)
/// and the unbalanced force (round-off) elsewhere.
/// Connected bond clusters that carry no support, no prescribed motion and no load stay at rest
/// (as in the explicit run); a loaded cluster without supports, or supports that leave a
/// rigid-body mode free, throw InputError.
StaticResult solve_static(Model& model, const StaticSettings& settings = {});
} // namespace dembridge::dem
