#include "coupling/multipliers.h"
#include <cmath>
#include <stdexcept>
#include <utility>

namespace dembridge::coupling
{
namespace
{
double dot(const std::vector<double>& a, const std::vector<double>& b)
{
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    s += a[i] * b[i];
  return s;
}
} // namespace

void MultiplierSolver::setup(const PointTransfer& transfer,
                             std::vector<double> particle_inverse_mass,
                             std::vector<double> slot_inverse_mass, const Tying tying,
                             const ConstraintSolve solve, const double tolerance,
                             const unsigned int max_iterations)
{
  if (tying == Tying::node && transfer.parallel())
    throw std::runtime_error("Coupling/tying: node tying runs on one process only (use "
                             "'particle' under mpirun)");
  G_ = &transfer;
  inv_m_ = std::move(particle_inverse_mass);
  inv_M_ = std::move(slot_inverse_mass);
  tying_ = tying;
  solve_ = solve;
  tolerance_ = tolerance;
  max_iterations_ = max_iterations;
  const std::size_t n =
      tying_ == Tying::particle ? 3 * transfer.n_points() : 3 * transfer.n_slots();
  for (auto* v : {&b_, &x_, &r_, &z_, &p_, &Ap_})
    v->assign(n, 0.0);
  Sq_.assign(3 * transfer.n_points(), 0.0);
  points_.assign(3 * transfer.n_points(), 0.0);
  slots_.assign(3 * transfer.n_slots(), 0.0);
  slots2_ = slots_;
  // A 1: the row sums of the constraint matrix (its entries are non-negative for FE_Q1 shape
  // values, so this is the usual row-sum lumping).
  std::vector<double> ones(n, 1.0);
  diagonal_.assign(n, 0.0);
  apply_constraint_matrix(ones, diagonal_);
  for (const double d : diagonal_)
    if (!(d > 0))
      throw std::runtime_error("Coupling: a tie has no stiffness to act on (zero row in the "
                               "lumped constraint matrix)");
  if (solve_ == ConstraintSolve::exact && tying_ == Tying::particle && !transfer.parallel())
    factorise();
}

// S^c = G diag(M^-1_c) G^T + diag(1 / m_p) per component c, from the rows of G: each slot's
// points couple pairwise.
void MultiplierSolver::factorise()
{
  const std::size_t n = G_->n_points();
  const auto& ptr = G_->row_pointers();
  const auto& slot = G_->row_slots();
  const auto& value = G_->row_values();
  std::vector<std::vector<std::pair<int, double>>> at_slot(G_->n_slots());
  for (std::size_t p = 0; p < n; ++p)
    for (unsigned int k = ptr[p]; k < ptr[p + 1]; ++k)
      at_slot[slot[k]].emplace_back(int(p), value[k]);
  for (int c = 0; c < 3; ++c)
  {
    std::vector<Eigen::Triplet<double>> t;
    for (std::size_t s = 0; s < at_slot.size(); ++s)
      for (const auto& [p, Np] : at_slot[s])
        for (const auto& [q, Nq] : at_slot[s])
          t.emplace_back(p, q, Np * Nq * inv_M_[3 * s + c]);
    for (std::size_t p = 0; p < n; ++p)
      t.emplace_back(int(p), int(p), inv_m_[p]);
    S_[c].resize(long(n), long(n));
    S_[c].setFromTriplets(t.begin(), t.end());
    factor_[c] = std::make_unique<Eigen::SimplicialLLT<Sparse>>(S_[c]);
    if (factor_[c]->info() != Eigen::Success)
      throw std::runtime_error("Coupling: the tie's constraint matrix is not positive definite");
  }
  rhs_.resize(long(n));
  sol_.resize(long(n));
}

void MultiplierSolver::apply_schur(const std::vector<double>& x, std::vector<double>& y)
{
  G_->spread(x, slots_);
  G_->assemble(slots_);
  for (std::size_t k = 0; k < slots_.size(); ++k)
    slots_[k] *= inv_M_[k];
  G_->interpolate(slots_, y);
  for (std::size_t p = 0; p < inv_m_.size(); ++p)
    for (int c = 0; c < 3; ++c)
      y[3 * p + c] += inv_m_[p] * x[3 * p + c];
}

void MultiplierSolver::apply_constraint_matrix(const std::vector<double>& x, std::vector<double>& y)
{
  if (tying_ == Tying::particle)
  {
    apply_schur(x, y);
    return;
  }
  G_->interpolate(x, points_); // G lambda
  apply_schur(points_, Sq_);   // S G lambda (Sq_ as work)
  G_->spread(Sq_, y);          // G^T S G lambda (one process: nothing to assemble)
}

unsigned int MultiplierSolver::solve(const std::vector<double>& rho, const double dt,
                                     std::vector<double>& q)
{
  const std::size_t n = b_.size();
  if (tying_ == Tying::particle)
    for (std::size_t i = 0; i < n; ++i)
      b_[i] = rho[i] / dt;
  else
  {
    G_->spread(rho, b_);
    for (auto& v : b_)
      v /= dt;
  }
  for (std::size_t i = 0; i < n; ++i)
    x_[i] = b_[i] / diagonal_[i]; // the lumped solve, and the start of CG
  unsigned int iterations = 0;
  residual_ = 0;
  if (factor_[0]) // S factorised: q = S^-1 b per component; S q = b to round-off
  {
    const std::size_t np = n / 3;
    for (int c = 0; c < 3; ++c)
    {
      for (std::size_t p = 0; p < np; ++p)
        rhs_[long(p)] = b_[3 * p + c];
      sol_ = factor_[c]->solve(rhs_);
      for (std::size_t p = 0; p < np; ++p)
        q[3 * p + c] = sol_[long(p)];
    }
    Sq_ = b_;
    return 0;
  }
  if (solve_ == ConstraintSolve::exact)
  {
    // Preconditioned conjugate gradients, preconditioner diag(A 1).
    const double b_norm = std::sqrt(dot(b_, b_));
    apply_constraint_matrix(x_, Ap_);
    for (std::size_t i = 0; i < n; ++i)
    {
      r_[i] = b_[i] - Ap_[i];
      z_[i] = r_[i] / diagonal_[i];
      p_[i] = z_[i];
    }
    double rz = dot(r_, z_);
    residual_ = b_norm > 0 ? std::sqrt(dot(r_, r_)) / b_norm : 0.0;
    for (;;)
    {
      char stop = residual_ <= tolerance_ || iterations >= max_iterations_;
      if (G_->parallel()) // every rank holds the same numbers; rank 0 decides
        MPI_Bcast(&stop, 1, MPI_CHAR, 0, G_->communicator());
      if (stop)
        break;
      apply_constraint_matrix(p_, Ap_);
      const double alpha = rz / dot(p_, Ap_);
      for (std::size_t i = 0; i < n; ++i)
      {
        x_[i] += alpha * p_[i];
        r_[i] -= alpha * Ap_[i];
        z_[i] = r_[i] / diagonal_[i];
      }
      const double rz_new = dot(r_, z_);
      for (std::size_t i = 0; i < n; ++i)
        p_[i] = z_[i] + (rz_new / rz) * p_[i];
      rz = rz_new;
      residual_ = std::sqrt(dot(r_, r_)) / b_norm;
      ++iterations;
    }
  }
  if (tying_ == Tying::particle)
    q = x_;
  else
    G_->interpolate(x_, q);
  apply_schur(q, Sq_);
  return iterations;
}
} // namespace dembridge::coupling
