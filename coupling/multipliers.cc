#include "coupling/multipliers.h"
#include <algorithm>
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
  // a setup starts afresh (an adaptive region sets the tie up again after each growth)
  factorised_ = false;
  for (int c = 0; c < 3; ++c)
    blocks_[c].clear(), factor_[c].reset();
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
  if (solve_ == ConstraintSolve::exact && tying_ == Tying::particle)
    factorise(); // on every rank alike: each holds the whole interface (transfer.h)
}

// S^c = D + G W_c G^T per component c, D = diag(1 / m_p), W_c = diag(M^-1) at the slots, is
// solved through the Woodbury identity on the slots (the FE nodes the interface touches):
//   S^-1 = D^-1 - D^-1 G_c A_c^-1 G_c^T D^-1,   A_c = W_c^-1 + G_c^T D^-1 G_c,
// with G_c the columns of the slots that move in component c (M^-1 > 0; a fixed DoF takes no
// impulse). A_c is the nodes' lumped mass plus the particles' mass shared onto them,
// A_st = M_s delta_st + sum_p m_p N_ps N_pt: FE-like sparsity over about a third as many slots
// as there are points, where S couples every pair of points that share a node (its factor was
// nearly dense over the band). On the bending beam's 600 interface particles and 200 slots the
// step's solve costs about a tenth of the pair of triangular solves with S.
void MultiplierSolver::factorise()
{
  const std::size_t n_slots = G_->n_slots();
  // Usually M^-1 is the same in the three components at every slot (they differ only where a
  // support fixes some of a node's components): then one factor serves all three, and each step
  // is one pair of triangular solves with three right-hand sides.
  shared_factor_ = true;
  for (std::size_t k = 0; k < n_slots; ++k)
    shared_factor_ =
        shared_factor_ && inv_M_[3 * k] == inv_M_[3 * k + 1] && inv_M_[3 * k] == inv_M_[3 * k + 2];
  for (int c = 0; c < (shared_factor_ ? 1 : 3); ++c)
  {
    const Sparse A = slot_matrix(c);
    // A few hundred slots (a band across a beam) are inverted densely, per connected group of
    // slots: a step's solve is then one matrix-vector product per group, at the speed of dense
    // arithmetic without the blocking overhead of small triangular solves (measured on the
    // bending beam's two bands of 100 slots: 6 % of the run with one 200 x 200 Cholesky factor,
    // two triangular solves of three right-hand sides per step). A larger band keeps the
    // sparse factor's memory.
    bool ok = true;
    if (n_slots <= dense_slots)
      ok = invert_dense_blocks(A, c);
    else
    {
      factor_[c] = std::make_unique<Eigen::SimplicialLLT<Sparse>>(A);
      ok = factor_[c]->info() == Eigen::Success;
    }
    if (!ok)
      throw std::runtime_error("Coupling: the tie's constraint matrix is not positive definite");
  }
  factorised_ = true;
  any_fixed_slot_ = false;
  for (const double w : inv_M_)
    any_fixed_slot_ = any_fixed_slot_ || !(w > 0);
  rhs_.resize(long(n_slots), shared_factor_ ? 3 : 1);
  sol_.resize(long(n_slots), shared_factor_ ? 3 : 1);
  check_factorised_solve();
}

// A_c = W_c^-1 + G_c^T D^-1 G_c over the slots; a fixed slot (M^-1 = 0 in component c) has
// A_kk = 1 and no coupling, so that y_k = 0.
MultiplierSolver::Sparse MultiplierSolver::slot_matrix(const int c) const
{
  const std::size_t n = G_->n_points(), n_slots = G_->n_slots();
  const auto& ptr = G_->row_pointers();
  const auto& slot = G_->row_slots();
  const auto& value = G_->row_values();
  const auto moves = [&](const std::size_t k) { return inv_M_[3 * k + c] > 0; };
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t p = 0; p < n; ++p)
    for (unsigned int i = ptr[p]; i < ptr[p + 1]; ++i)
      for (unsigned int j = ptr[p]; j < ptr[p + 1]; ++j)
        if (moves(slot[i]) && moves(slot[j]))
          t.emplace_back(int(slot[i]), int(slot[j]), value[i] * value[j] / inv_m_[p]);
  for (std::size_t k = 0; k < n_slots; ++k)
    t.emplace_back(int(k), int(k), moves(k) ? 1.0 / inv_M_[3 * k + c] : 1.0);
  Sparse A{long(n_slots), long(n_slots)};
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

namespace
{
/// The connected groups of the slots' graph (@p A's sparsity): each slot's group, numbered from
/// 0 in the order of their first slots; @p n_groups receives their count.
std::vector<int> connected_groups(const Eigen::SparseMatrix<double>& A, int& n_groups)
{
  const std::size_t n_slots = std::size_t(A.rows());
  std::vector<int> group(n_slots, -1);
  n_groups = 0;
  for (std::size_t start = 0; start < n_slots; ++start)
  {
    if (group[start] >= 0)
      continue;
    std::vector<long> stack{long(start)};
    group[start] = n_groups;
    while (!stack.empty())
    {
      const long k = stack.back();
      stack.pop_back();
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
        if (group[it.row()] < 0)
        {
          group[it.row()] = n_groups;
          stack.push_back(it.row());
        }
    }
    ++n_groups;
  }
  return group;
}
} // namespace

// A_c^-1 per connected group of slots, dense; false when a group's Cholesky factor fails.
bool MultiplierSolver::invert_dense_blocks(const Sparse& A, const int c)
{
  const std::size_t n_slots = G_->n_slots();
  int n_groups = 0;
  const std::vector<int> group = connected_groups(A, n_groups);
  blocks_[c].assign(n_groups, {});
  for (std::size_t k = 0; k < n_slots; ++k)
    blocks_[c][group[k]].slots.push_back((unsigned int)(k));
  const Eigen::MatrixXd dense(A);
  bool ok = true;
  for (auto& b : blocks_[c])
  {
    const long m = long(b.slots.size());
    Eigen::MatrixXd Ab(m, m);
    for (long i = 0; i < m; ++i)
      for (long j = 0; j < m; ++j)
        Ab(i, j) = dense(b.slots[i], b.slots[j]);
    const Eigen::LLT<Eigen::MatrixXd> llt(Ab);
    ok = ok && llt.info() == Eigen::Success;
    const Eigen::MatrixXd inverse = llt.solve(Eigen::MatrixXd::Identity(m, m));
    b.inverse.resize(std::size_t(m * m));
    for (long i = 0; i < m; ++i)
      for (long j = 0; j < m; ++j)
        b.inverse[std::size_t(i * m + j)] = inverse(i, j);
    block_rhs_.resize(std::max(block_rhs_.size(), std::size_t(3 * m)));
    block_y_.resize(block_rhs_.size());
  }
  return ok;
}

// S q = b to round-off for a b with every component and scale (a check of the identity's use).
void MultiplierSolver::check_factorised_solve()
{
  const std::size_t n = G_->n_points();
  std::vector<double> b(3 * n), q(3 * n), Sq(3 * n);
  for (std::size_t i = 0; i < b.size(); ++i)
    b[i] = std::sin(1.0 + 0.7 * double(i)) / inv_m_[i / 3];
  solve_factorised(b, q);
  apply_schur(q, Sq);
  double error = 0, scale = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    error = std::max(error, std::abs(Sq[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  if (!(error <= 1e-9 * scale))
    throw std::logic_error("Coupling: the factorised tie solve misses S q = b by " +
                           std::to_string(error / scale) + " (relative)");
}

// q = S^-1 b by the Woodbury form above: q_p = m_p (b_p - sum_s N_ps y_s), A y = G^T (m b).
void MultiplierSolver::solve_factorised(const std::vector<double>& b, std::vector<double>& q)
{
  const std::size_t n = G_->n_points(), n_slots = G_->n_slots();
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c)
      points_[3 * p + c] = b[3 * p + c] / inv_m_[p];
  G_->spread(points_, slots_);
  if (!blocks_[0].empty())
    solve_blocks();
  else
    for (int c = 0; c < 3; ++c)
    {
      const int column = shared_factor_ ? c : 0;
      for (std::size_t k = 0; k < n_slots; ++k)
        rhs_(long(k), column) = inv_M_[3 * k + c] > 0 ? slots_[3 * k + c] : 0.0;
      if (!shared_factor_ || c == 2)
      {
        const int f = shared_factor_ ? 0 : c;
        sol_ = factor_[f]->solve(rhs_);
        for (std::size_t k = 0; k < n_slots; ++k)
          for (int d = shared_factor_ ? 0 : c; d <= c; ++d)
            slots_[3 * k + d] = sol_(long(k), shared_factor_ ? d : 0);
      }
    }
  G_->interpolate(slots_, points_);
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c)
      q[3 * p + c] = (b[3 * p + c] - points_[3 * p + c]) / inv_m_[p];
}

namespace
{
/// y_e = A^-1 r_e for E right-hand sides of length m (SoA), A^-1 symmetric (its rows are its
/// columns): y = sum_j (column j) r_j, the updates running along i in lanes (a dot product per
/// row would be a reduction, which strict floating point keeps scalar). Rows go in chunks of
/// 16 whose E sums stay in registers over the whole j loop, instead of a load and a store of y
/// for every column; each y_i still sums in column order.
template <int E>
void block_product(const double* __restrict inverse, const std::size_t m,
                   const double* __restrict r, double* __restrict y)
{
  constexpr std::size_t chunk = 16;
  for (std::size_t i0 = 0; i0 < m; i0 += chunk)
  {
    if (i0 + chunk <= m)
    {
      double sum[E][chunk] = {};
      for (std::size_t j = 0; j < m; ++j)
      {
        const double* __restrict column = inverse + j * m + i0;
        for (int e = 0; e < E; ++e)
        {
          const double rj = r[e * m + j];
          // why: deal.II's flags end in -O2, where GCC 12 vectorises only the cheapest loops
#pragma omp simd
          for (std::size_t i = 0; i < chunk; ++i)
            sum[e][i] += column[i] * rj;
        }
      }
      for (int e = 0; e < E; ++e)
        for (std::size_t i = 0; i < chunk; ++i)
          y[e * m + i0 + i] = sum[e][i];
      continue;
    }
    const std::size_t rows = m - i0; // the last, shorter chunk
    for (int e = 0; e < E; ++e)
      std::fill(y + e * m + i0, y + e * m + m, 0.0);
    for (std::size_t j = 0; j < m; ++j)
      for (int e = 0; e < E; ++e)
      {
        const double rj = r[e * m + j];
#pragma omp simd
        for (std::size_t i = 0; i < rows; ++i)
          y[e * m + i0 + i] += inverse[j * m + i0 + i] * rj;
      }
  }
}
} // namespace

// slots_ = A^-1 slots_ per component, group by group (the right-hand side zero on a slot
// component that does not move, where A is the identity and y = 0).
void MultiplierSolver::solve_blocks()
{
  for (int c0 = 0; c0 < 3; ++c0)
  {
    if (shared_factor_ && c0 > 0)
      break;
    const int n_components = shared_factor_ ? 3 : 1;
    for (const auto& b : blocks_[c0])
    {
      const std::size_t m = b.slots.size();
      double* r = block_rhs_.data();
      for (int e = 0; e < n_components; ++e)
        for (std::size_t j = 0; j < m; ++j)
        {
          const std::size_t i = 3 * b.slots[j] + (shared_factor_ ? e : c0);
          r[e * m + j] = inv_M_[i] > 0 ? slots_[i] : 0.0;
        }
      double* y = block_y_.data();
      if (n_components == 3)
        block_product<3>(b.inverse.data(), m, r, y);
      else
        block_product<1>(b.inverse.data(), m, r, y);
      for (std::size_t i = 0; i < m; ++i)
        for (int e = 0; e < n_components; ++e)
          slots_[3 * b.slots[i] + (shared_factor_ ? e : c0)] = y[e * m + i];
    }
  }
}

bool MultiplierSolver::slot_reaction(std::vector<double>& slots) const
{
  // G^T q = G^T D^-1 (b - G y) = G^T D^-1 b - (A - W^-1) y = W^-1 y = M y on the slot
  // components that move (A y = G^T D^-1 b there); a fixed component needs the spread
  if (!factorised_ || any_fixed_slot_)
    return false;
  slots.resize(slots_.size()); // slots_ still holds y: nothing since solve() has used it
  for (std::size_t k = 0; k < slots_.size(); ++k)
    slots[k] = -slots_[k] / inv_M_[k];
  return true;
}

void MultiplierSolver::apply_schur(const std::vector<double>& x, std::vector<double>& y)
{
  G_->spread(x, slots_);
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
  G_->spread(Sq_, y);          // G^T S G lambda
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
  residual_ = 0;
  if (factorised_) // S factorised: q = S^-1 b; S q = b to round-off
  {
    solve_factorised(b_, q);
    Sq_ = b_;
    return 0;
  }
  for (std::size_t i = 0; i < n; ++i)
    x_[i] = b_[i] / diagonal_[i]; // the lumped solve, and the start of CG
  unsigned int iterations = 0;
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
