// dembridge::fem — K u cell by cell, and the element eigenvalue bound (element_operator.h).
#include "fem/element_operator.h"
#include "fem/local_array.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dembridge::fem
{
using namespace dealii;

namespace
{
/// Two element matrices are one when they agree to this, relative to their largest entry: the
/// same shape and weights give the same K_e to a few units of round-off.
constexpr double same_matrix = 1e-12;
constexpr std::size_t max_groups = 20000;
} // namespace

void ElementOperator::reinit(const IndexSet& owned, const IndexSet& relevant,
                             const unsigned int dofs_per_cell, MPI_Comm comm)
{
  active_ = dofs_per_cell == cell_size;
  comm_ = comm;
  parallel_ = Utilities::MPI::n_mpi_processes(comm) > 1;
  owned_ = owned;
  ghosts_ = relevant;
  ghosts_.subtract_set(owned);
  n_owned_ = owned.n_elements();
  groups_.clear();
  group_index_.clear();
  n_cells_ = 0;
  cell_mass_.clear();
  if (parallel_ && active_)
    accumulate_.reinit(owned, ghosts_, comm);
}

std::uint32_t ElementOperator::local_index(const types::global_dof_index i) const
{
  if (owned_.is_element(i))
    return std::uint32_t(owned_.index_within_set(i));
  if (!ghosts_.is_element(i))
    throw std::logic_error("ElementOperator: a cell DoF is neither owned nor a ghost");
  return std::uint32_t(n_owned_ + ghosts_.index_within_set(i));
}

// Candidates are found by a key of the matrix's diagonal rounded to 8 digits of its largest
// entry, then compared entry by entry; two equal matrices that round apart only make two groups.
std::uint64_t ElementOperator::group_key(const CellMatrix& m)
{
  const double scale = m.cwiseAbs().maxCoeff();
  int exponent = 0;
  std::uint64_t key = std::uint64_t(std::llround(std::frexp(scale, &exponent) * 1e8)) ^
                      (std::uint64_t(exponent + 2048) << 40);
  for (unsigned int i = 0; i < cell_size; ++i)
    key = key * 1000003u + std::uint64_t(std::llround(m(i, i) / scale * 1e8));
  return key;
}

std::size_t ElementOperator::find_group(const CellMatrix& m, const std::uint64_t key) const
{
  const double scale = m.cwiseAbs().maxCoeff();
  const auto [first, last] = group_index_.equal_range(key);
  for (auto it = first; it != last; ++it)
    if ((groups_[it->second].matrix - m).cwiseAbs().maxCoeff() <= same_matrix * scale)
      return it->second;
  return groups_.size();
}

void ElementOperator::add_cell(const std::vector<types::global_dof_index>& dofs,
                               const FullMatrix<double>& cell_matrix)
{
  if (!active_)
    return;
  CellMatrix m;
  for (unsigned int i = 0; i < cell_size; ++i)
    for (unsigned int j = 0; j < cell_size; ++j)
      m(i, j) = 0.5 * (cell_matrix(i, j) + cell_matrix(j, i));
  // A few dozen shapes in a graded box mesh, plus the band's weighted cells. Beyond
  // max_groups distinct matrices (an unstructured mesh) the product cell by cell would stream as
  // much matrix as the assembled one: the operator stays inactive.
  const std::uint64_t key = group_key(m);
  const std::size_t g = find_group(m, key);
  if (g == groups_.size())
  {
    if (groups_.size() >= max_groups)
    {
      active_ = false;
      groups_.clear();
      group_index_.clear();
      return;
    }
    groups_.push_back({m, {}, {}});
    group_index_.emplace(key, g);
  }
  groups_[g].cells.push_back(std::uint32_t(n_cells_++));
  for (const auto i : dofs)
    groups_[g].dofs.push_back(local_index(i));
}

void ElementOperator::add_cell_mass(const Vector<double>& cell_mass)
{
  if (!active_)
    return;
  for (unsigned int i = 0; i < cell_size; ++i)
    cell_mass_.push_back(cell_mass(i));
}

void ElementOperator::vmult(LA::MPI::Vector& y, const LA::MPI::Vector& u) const
{
  LocalArray in(u);
  LocalArray out(parallel_ ? accumulate_ : y);
  const double* x = in.data();
  double* r = out.data();
  std::fill(r, r + out.size(), 0.0);
  // y_e = sum_j K_e(:, j) x_j: each column of K_e (three AVX-512 registers) times a broadcast
  // entry; Eigen's general product would pack the operands of so small a product first. Four
  // cells of a group at a time: one cell's sum is a chain of 24 dependent multiply-adds per
  // register; four independent chains keep the pipeline fuller (11 % less time on the coupled
  // bending beam's continuum; the scatter into y, 40 % of the time, is unchanged). Every cell
  // still sums in column order and adds into y in cell order: the one-cell loop's bits.
  using Column = Eigen::Matrix<double, cell_size, 1>;
  const auto add_into = [r](const Column& y, const std::uint32_t* d)
  {
    for (unsigned int i = 0; i < cell_size; ++i)
      r[d[i]] += y(i);
  };
  for (const auto& g : groups_)
  {
    const std::size_t n = g.cells.size();
    const std::uint32_t* d = g.dofs.data();
    std::size_t c = 0;
    for (; c + 4 <= n; c += 4, d += 4 * cell_size)
    {
      const std::uint32_t *d1 = d + cell_size, *d2 = d1 + cell_size, *d3 = d2 + cell_size;
      Column y0 = g.matrix.col(0) * x[d[0]], y1 = g.matrix.col(0) * x[d1[0]],
             y2 = g.matrix.col(0) * x[d2[0]], y3 = g.matrix.col(0) * x[d3[0]];
      for (unsigned int j = 1; j < cell_size; ++j)
      {
        const Column k = g.matrix.col(j);
        y0.noalias() += k * x[d[j]];
        y1.noalias() += k * x[d1[j]];
        y2.noalias() += k * x[d2[j]];
        y3.noalias() += k * x[d3[j]];
      }
      add_into(y0, d);
      add_into(y1, d1);
      add_into(y2, d2);
      add_into(y3, d3);
    }
    for (; c < n; ++c, d += cell_size)
    {
      Column y = g.matrix.col(0) * x[d[0]];
      for (unsigned int j = 1; j < cell_size; ++j)
        y.noalias() += g.matrix.col(j) * x[d[j]];
      add_into(y, d);
    }
  }
  if (!parallel_)
    return;
  add_ghosts_to_owners(accumulate_);
  LocalArray sum(accumulate_), owned(y);
  for (std::size_t i = 0; i < n_owned_; ++i)
    owned[i] = sum[i];
}

double ElementOperator::frequency_bound(const LA::MPI::Vector& mass_scale,
                                        const LA::MPI::Vector& free) const
{
  if (cell_mass_.size() != n_cells_ * cell_size)
    throw std::logic_error("ElementOperator: cell masses missing for the frequency bound");
  LocalArray scale(mass_scale), moves(free);
  Eigen::SelfAdjointEigenSolver<CellMatrix> eigen;
  double bound = 0;
  for (const auto& g : groups_)
    for (std::size_t k = 0; k < g.cells.size(); ++k)
    {
      const std::uint32_t* d = &g.dofs[k * cell_size];
      const double* m = &cell_mass_[std::size_t(g.cells[k]) * cell_size];
      Eigen::Matrix<double, cell_size, 1> s; // D_e^-1/2, 0 on DoFs that do not move
      bool any = false;
      for (unsigned int i = 0; i < cell_size; ++i)
      {
        const double mass = m[i] * scale[d[i]];
        const bool moving = moves[d[i]] > 0 && mass > 0;
        s(i) = moving ? 1.0 / std::sqrt(mass) : 0.0;
        any = any || moving;
      }
      if (!any)
        continue;
      const CellMatrix a = s.asDiagonal() * g.matrix * s.asDiagonal();
      eigen.compute(a, Eigen::EigenvaluesOnly);
      bound = std::max(bound, eigen.eigenvalues().maxCoeff());
    }
  return Utilities::MPI::max(bound, comm_);
}
} // namespace dembridge::fem
