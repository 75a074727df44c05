#include "coupling/transfer.h"
#include "fem/local_array.h"

#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/fe/fe_q.h>

#include <petscvec.h>

#include <map>
#include <sstream>
#include <stdexcept>

namespace dembridge::coupling
{
using namespace dealii;

namespace
{
using Locator = Utilities::MPI::RemotePointEvaluation<3>;

/// Throws "<where>: the interface point (...) lies outside the FE mesh" for the first of @p at
/// (rank 0's points) that @p locator did not find (collective).
void require_points_found(const Locator& locator, const std::vector<Point<3>>& at, MPI_Comm comm,
                          const std::string& where)
{
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
  long missing = -1;
  if (rank == 0)
    for (std::size_t p = 0; p < at.size() && missing < 0; ++p)
      if (!locator.point_found(p))
        missing = long(p);
  missing = Utilities::MPI::broadcast(comm, missing, 0);
  if (missing >= 0)
  {
    const auto x = Utilities::MPI::broadcast(comm, rank == 0 ? at[missing] : Point<3>(), 0);
    std::ostringstream s;
    s << where << ": the interface point (" << x[0] << ", " << x[1] << ", " << x[2]
      << ") lies outside the FE mesh";
    throw std::runtime_error(s.str());
  }
}

/// This rank's rows of G: for each point the (slot, N_I(xi_p)) of the nodes its cell gives a
/// non-zero shape value, the slots numbered as first met, with their x, y, z DoFs and
/// positions.
struct ShapeRows
{
  std::vector<std::vector<std::pair<unsigned int, double>>> rows; ///< one per point (all ranks')
  std::vector<types::global_dof_index> slot_dofs;                 ///< 3 per slot
  std::vector<Point<3>> slot_points;
  std::size_t n_slots = 0;
};

ShapeRows shape_rows(const fem::ExplicitDynamics& fe, Locator& locator, std::size_t n_given,
                     std::size_t n_points)
{
  // Which point each of this rank's (cell, reference point) pairs is: send the point indices
  // along the same route the values take.
  std::vector<double> index(n_given);
  for (std::size_t p = 0; p < n_given; ++p)
    index[p] = double(p);
  std::vector<double> buffer;
  const auto& dof_handler = fe.get_dof_handler();
  const auto& fe_system = fe.get_fe();
  const auto& base = fe_system.base_element(0);
  const unsigned int n_base = base.n_dofs_per_cell();
  std::map<types::global_dof_index, unsigned int> slot_of; // x-DoF of a node -> slot
  ShapeRows r;
  r.rows.resize(n_points);
  std::vector<types::global_dof_index> cell_dofs(fe_system.n_dofs_per_cell());
  locator.process_and_evaluate<double>(
      index, buffer,
      [&](const ArrayView<const double>& values, const Locator::CellData& cell_data)
      {
        for (unsigned int c = 0; c < cell_data.cells.size(); ++c)
        {
          const typename DoFHandler<3>::active_cell_iterator cell(
              &fe.get_triangulation(), cell_data.cells[c].first, cell_data.cells[c].second,
              &dof_handler);
          cell->get_dof_indices(cell_dofs);
          for (unsigned int q = cell_data.reference_point_ptrs[c];
               q < cell_data.reference_point_ptrs[c + 1]; ++q)
          {
            const auto p = static_cast<std::size_t>(values[q] + 0.5);
            const Point<3>& xi = cell_data.reference_point_values[q];
            for (unsigned int b = 0; b < n_base; ++b)
            {
              const double N = base.shape_value(b, xi);
              if (std::abs(N) < 1e-14)
                continue;
              const auto dof_x = cell_dofs[fe_system.component_to_system_index(0, b)];
              auto [it, fresh] = slot_of.emplace(dof_x, unsigned(slot_of.size()));
              if (fresh)
              {
                for (unsigned int d = 0; d < 3; ++d)
                  r.slot_dofs.push_back(cell_dofs[fe_system.component_to_system_index(d, b)]);
                r.slot_points.push_back(fe.get_mapping().transform_unit_to_real_cell(
                    cell, base.get_unit_support_points()[b]));
              }
              r.rows[p].emplace_back(it->second, N);
            }
          }
        }
      });
  r.n_slots = slot_of.size();
  return r;
}
} // namespace

void PointTransfer::reinit(const fem::ExplicitDynamics& fe, const std::vector<dem::Vec3>& points,
                           const std::string& where)
{
  comm_ = fe.communicator();
  parallel_ = Utilities::MPI::n_mpi_processes(comm_) > 1;
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm_);
  if (rank != 0 && !points.empty())
    throw std::runtime_error(where + ": interface points must be given on rank 0");
  n_points_ = Utilities::MPI::broadcast(comm_, points.size(), 0);

  std::vector<Point<3>> at;
  for (const auto& x : points)
    at.emplace_back(x[0], x[1], x[2]);
  Locator locator(1e-6, /*enforce_unique_mapping=*/true);
  locator.reinit(at, fe.get_triangulation(), fe.get_mapping());
  require_points_found(locator, at, comm_, where);

  ShapeRows r = shape_rows(fe, locator, at.size(), n_points_);
  slot_point_ = std::move(r.slot_points); // a reinit starts afresh
  store_rows(r.rows, r.n_slots);
  index_slot_dofs(fe, r.slot_dofs, where);
}

// The rows as compressed rows (interpolation) and by slot (G^T in compressed columns, points
// ascending within each slot: spreading).
void PointTransfer::store_rows(
    const std::vector<std::vector<std::pair<unsigned int, double>>>& rows, std::size_t n_slots)
{
  row_ptr_.assign(1, 0);
  row_slot_.clear();
  row_value_.clear();
  for (const auto& row : rows)
  {
    for (const auto& [slot, N] : row)
      row_slot_.push_back(slot), row_value_.push_back(N);
    row_ptr_.push_back(unsigned(row_slot_.size()));
  }
  col_ptr_.assign(n_slots + 1, 0);
  for (const unsigned int slot : row_slot_)
    ++col_ptr_[slot + 1];
  for (std::size_t k = 0; k < n_slots; ++k)
    col_ptr_[k + 1] += col_ptr_[k];
  col_point_.resize(row_slot_.size());
  col_value_.resize(row_slot_.size());
  std::vector<unsigned int> next(col_ptr_.begin(), col_ptr_.end() - 1);
  for (std::size_t p = 0; p + 1 < row_ptr_.size(); ++p)
    for (unsigned int k = row_ptr_[p]; k < row_ptr_[p + 1]; ++k)
    {
      const unsigned int at = next[row_slot_[k]]++;
      col_point_[at] = unsigned(p);
      col_value_[at] = row_value_[k];
    }
}

// Local-form positions of the slot DoFs.
void PointTransfer::index_slot_dofs(const fem::ExplicitDynamics& fe,
                                    const std::vector<dealii::types::global_dof_index>& slot_dofs,
                                    const std::string& where)
{
  ghosted_.reinit(fe.owned_dofs(), fe.relevant_dofs(), comm_);
  const IndexSet& owned = fe.owned_dofs();
  const auto first = owned.n_elements() > 0 ? owned.nth_index_in_set(0) : 0;
  IndexSet ghosts = fe.relevant_dofs(); // the ghosts in PETSc's order (sorted)
  ghosts.subtract_set(owned);
  slot_local_.clear();
  for (const auto dof : slot_dofs)
  {
    if (owned.is_element(dof))
      slot_local_.push_back(unsigned(dof - first));
    else if (parallel_ && ghosts.is_element(dof))
      slot_local_.push_back(unsigned(owned.n_elements() + ghosts.index_within_set(dof)));
    else
      throw std::runtime_error(where + ": an interface node is neither owned nor a ghost");
  }
}

void PointTransfer::gather(const fem::LA::MPI::Vector& x, std::vector<double>& slots) const
{
  slots.resize(slot_local_.size());
  if (parallel_)
  {
    ghosted_ = x; // copies the owned part and updates the ghosts
    fem::LocalArray a(ghosted_);
    for (std::size_t k = 0; k < slot_local_.size(); ++k)
      slots[k] = a[slot_local_[k]];
  }
  else
  {
    fem::LocalArray a(x);
    for (std::size_t k = 0; k < slot_local_.size(); ++k)
      slots[k] = a[slot_local_[k]];
  }
}

void PointTransfer::scatter_add(const std::vector<double>& slots, fem::LA::MPI::Vector& f) const
{
  if (!parallel_)
  {
    fem::LocalArray a(f);
    for (std::size_t k = 0; k < slot_local_.size(); ++k)
      a[slot_local_[k]] += slots[k];
    return;
  }
  {
    fem::LocalArray w(ghosted_);
    for (std::size_t i = 0; i < w.size(); ++i)
      w[i] = 0;
    for (std::size_t k = 0; k < slot_local_.size(); ++k)
      w[slot_local_[k]] += slots[k];
  }
  fem::add_ghosts_to_owners(ghosted_);
  fem::LocalArray w(ghosted_), a(f);
  const std::size_t n = fem::LA::MPI::Vector::size_type(f.locally_owned_size());
  for (std::size_t i = 0; i < n; ++i)
    a[i] += w[i];
}

void PointTransfer::assemble(std::vector<double>& slots) const
{
  if (!parallel_)
    return;
  {
    fem::LocalArray w(ghosted_);
    for (std::size_t i = 0; i < w.size(); ++i)
      w[i] = 0;
    for (std::size_t k = 0; k < slot_local_.size(); ++k)
      w[slot_local_[k]] += slots[k];
  }
  const Vec v = static_cast<const Vec&>(ghosted_);
  VecGhostUpdateBegin(v, ADD_VALUES, SCATTER_REVERSE);
  VecGhostUpdateEnd(v, ADD_VALUES, SCATTER_REVERSE);
  VecGhostUpdateBegin(v, INSERT_VALUES, SCATTER_FORWARD);
  VecGhostUpdateEnd(v, INSERT_VALUES, SCATTER_FORWARD);
  fem::LocalArray w(ghosted_);
  for (std::size_t k = 0; k < slot_local_.size(); ++k)
    slots[k] = w[slot_local_[k]];
}

void PointTransfer::interpolate(const std::vector<double>& slots, std::vector<double>& points) const
{
  points.resize(3 * n_points_);
  for (std::size_t p = 0; p < n_points_; ++p)
  {
    double x = 0, y = 0, z = 0; // in registers: points and slots may alias for the compiler
    for (unsigned int k = row_ptr_[p]; k < row_ptr_[p + 1]; ++k)
    {
      const double N = row_value_[k];
      const double* s = &slots[3 * row_slot_[k]];
      x += N * s[0];
      y += N * s[1];
      z += N * s[2];
    }
    points[3 * p] = x, points[3 * p + 1] = y, points[3 * p + 2] = z;
  }
  if (parallel_)
    MPI_Allreduce(MPI_IN_PLACE, points.data(), int(points.size()), MPI_DOUBLE, MPI_SUM, comm_);
}

// Slot by slot over G^T's columns: each slot's sum stays in registers (point by point over the
// rows, consecutive points add into the same slots, a chain through memory); the terms are
// added in the same order (points ascending).
void PointTransfer::spread(const std::vector<double>& points, std::vector<double>& slots) const
{
  slots.resize(slot_local_.size());
  const std::size_t n_slots = slot_local_.size() / 3;
  for (std::size_t s = 0; s < n_slots; ++s)
  {
    double x = 0, y = 0, z = 0;
    for (unsigned int k = col_ptr_[s]; k < col_ptr_[s + 1]; ++k)
    {
      const double N = col_value_[k];
      const double* v = &points[3 * std::size_t(col_point_[k])];
      x += N * v[0];
      y += N * v[1];
      z += N * v[2];
    }
    slots[3 * s] = x, slots[3 * s + 1] = y, slots[3 * s + 2] = z;
  }
}
} // namespace dembridge::coupling
