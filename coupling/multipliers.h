#pragma once
// The velocity tie of the bridging domain method (Xiao & Belytschko 2004, eq. 20-28) and the
// Lagrange multiplier solve of one explicit step.
//
// Constraint on the handshake band, for every interface particle p (reference centre X_p in an
// FE cell at reference coordinates xi_p), translations only:
//   sum_I N_I(xi_p) v_I = v_p                                         (velocities tied)
// Particle rotations stay free: a classical continuum has no rotation field to tie them to.
// Multipliers. Two discretisations of the multiplier field lambda(X):
//   particle tying  one multiplier per interface particle (collocation, the constraint above);
//   node tying      lambda(X) = sum_I N_I(X) lambda_I, one per FE node carrying particles: the
//                   constraint holds weakly, sum_p N_I(X_p) (sum_J N_J v_J - v_p) = 0 per node,
//                   and the part of the particle motion the FE field cannot represent is free
//                   (it can then be damped, coupled_problem.h). Both give the same result when
//                   every FE node sits on a particle (h = particle spacing, matched planes).
// With q_p the tie force on particle p (q = lambda, or q = G lambda for node tying), the FE nodes
// receive -G^T q (action and reaction), so the step's velocities are
//   v_I = v^_I - dt M^-1 G^T q,        v_p = v^_p + dt q_p / m_p
// from the unconstrained trial velocities v^. Writing S = G M^-1 G^T + diag(1/m_p) and
//   rho = G v^_I - v^_p + g^n / dt     (g^n = G u^n_I - u^n_p: the displacement gap, so that the
//                                      tie holds for displacements too and cannot drift)
// the multipliers solve
//   particle tying:  dt S q = rho
//   node tying:      dt (G^T S G) lambda = G^T rho,  q = G lambda
// and the gap after the step is g^{n+1} = dt (rho - dt S q) (zero when the solve is exact).
// Solves:
//   lumped  the constraint matrix A (S, or G^T S G) replaced by its row-sum diagonal A 1 (the
//           paper's choice: local, one division per multiplier); the tie is then met only
//           approximately each step, the gap term carries the rest into the next step;
//   exact   with particle tying: S is constant (fixed G and masses); its inverse is applied
//           through the Woodbury identity on the slots (multipliers.cc), whose small matrix is
//           inverted once per connected group of slots (dense up to 2000 slots, else a sparse
//           Cholesky factor); each step is a spread, one matrix-vector product per group and an
//           interpolation, and the FE nodes' share -G^T q = -M y needs no second spread. Under
//           MPI every rank holds the whole interface (transfer.h) and does the same: the solve
//           needs no communication. With node tying
//           conjugate gradients on A, the lumped diagonal as preconditioner, to a relative residual
//           `tolerance` (a few iterations: A is dominated by its particle-mass diagonal). On the
//           bending beam's 600 interface particles the factorised solve takes 8 % of the run where
//           CG to 1e-12 took 28 % (1.27x the run's speed).
// M^-1 is zero on fixed FE DoFs (they take no impulse). Units: q in N, v in m/s.
#include "coupling/transfer.h"
#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <array>
#include <memory>
#include <vector>

namespace dembridge::coupling
{
enum class Tying
{
  particle, ///< one multiplier per interface particle
  node      ///< multipliers interpolated by the FE shape functions (one process only)
};

enum class ConstraintSolve
{
  lumped, ///< row-sum diagonal of the constraint matrix
  exact   ///< factorised (particle tying) or preconditioned conjugate gradients to `tolerance`
};

class MultiplierSolver
{
public:
  /// @p particle_inverse_mass: 1 / (w_p m_p) per interface particle (every rank);
  /// @p slot_inverse_mass: M^-1 at the transfer's slots, 3 per slot.
  void setup(const PointTransfer& transfer, std::vector<double> particle_inverse_mass,
             std::vector<double> slot_inverse_mass, Tying tying, ConstraintSolve solve,
             double tolerance, unsigned int max_iterations);

  /// The tie forces q (3 per interface particle, every rank) for the residual rho; also leaves
  /// S q in `schur_q()` for the gap update. Every rank alike, no communication. Returns the CG
  /// iterations (0: lumped or factorised).
  unsigned int solve(const std::vector<double>& rho, double dt, std::vector<double>& q);
  const std::vector<double>& schur_q() const { return Sq_; }

  /// y = S x = G M^-1 G^T x + x / m.
  void apply_schur(const std::vector<double>& x, std::vector<double>& y);
  /// Lumped diagonal of the constraint matrix (per multiplier and component).
  const std::vector<double>& lumped_diagonal() const { return diagonal_; }
  /// Largest relative residual |A x - b| / |b| of the last solve (0 for a lumped solve).
  double last_residual() const { return residual_; }
  /// After a factorised solve (and before the next call of solve or apply_schur, which reuse
  /// the slot work vector that holds y): the FE nodes' force -G^T q at the slots, from
  /// G^T q = M y (multipliers.cc), so that no spread of q is needed; false otherwise (the
  /// caller spreads q itself).
  bool slot_reaction(std::vector<double>& slots) const;

private:
  void apply_constraint_matrix(const std::vector<double>& x, std::vector<double>& y);
  void factorise();
  void solve_factorised(const std::vector<double>& b, std::vector<double>& q);
  void solve_blocks();

  /// The slots' matrix A_c of the Woodbury form of S^-1 per component, factorised (particle
  /// tying, exact solve; multipliers.cc).
  using Sparse = Eigen::SparseMatrix<double>;
  static constexpr std::size_t dense_slots = 2000; ///< up to this many slots: dense inverses
  /// The steps of factorise() (multipliers.cc).
  Sparse slot_matrix(int c) const;
  bool invert_dense_blocks(const Sparse& A, int c);
  void check_factorised_solve();
  bool factorised_ = false;
  /// A_c^-1 of one connected group of slots (the bands of a region are separate groups), dense
  /// (symmetric: rows and columns alike): y = A^-1 r is then one matrix-vector product per step.
  struct DenseBlock
  {
    std::vector<unsigned int> slots;
    std::vector<double> inverse;
  };
  std::array<std::vector<DenseBlock>, 3> blocks_;
  bool any_fixed_slot_ = false;             ///< some slot component does not move
  std::vector<double> block_rhs_, block_y_; ///< work, 3 x largest block (SoA)
  std::array<std::unique_ptr<Eigen::SimplicialLLT<Sparse>>, 3> factor_;
  bool shared_factor_ = false; ///< one factor for the three components
  Eigen::MatrixXd rhs_, sol_;  ///< n_slots x 3 (shared factor) or n_slots x 1

  const PointTransfer* G_ = nullptr;
  std::vector<double> inv_m_, inv_M_;
  Tying tying_ = Tying::particle;
  ConstraintSolve solve_ = ConstraintSolve::exact;
  double tolerance_ = 1e-10;
  unsigned int max_iterations_ = 100;
  std::vector<double> diagonal_;
  double residual_ = 0;
  // work vectors (sized once)
  std::vector<double> slots_, slots2_, points_, Sq_, b_, x_, r_, z_, p_, Ap_;
};
} // namespace dembridge::coupling
