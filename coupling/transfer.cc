#include "coupling/transfer.h"
#include "fem/local_array.h"

#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/fe/fe_q.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
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

/// Every rank's rows on every rank (collective): the points' rows in point order, from the rank
/// that holds each point, over the nodes all of them touch, numbered as first met in that order:
/// the same numbering on every rank and on any number of ranks (so that a step's sums run in
/// the same order as on one).
ShapeRows shared_rows(const ShapeRows& mine, MPI_Comm comm)
{
  std::vector<types::global_dof_index> ids; // per entry: point, x, y and z DoF
  std::vector<double> values;               // per entry: N, node position
  for (std::size_t p = 0; p < mine.rows.size(); ++p)
    for (const auto& [slot, N] : mine.rows[p])
    {
      ids.push_back(p);
      for (unsigned int d = 0; d < 3; ++d)
        ids.push_back(mine.slot_dofs[3 * slot + d]);
      values.push_back(N);
      for (unsigned int d = 0; d < 3; ++d)
        values.push_back(mine.slot_points[slot][d]);
    }
  const auto all_ids = Utilities::MPI::all_gather(comm, ids);
  const auto all_values = Utilities::MPI::all_gather(comm, values);
  // each point's entries from the first rank that holds it (the locator gives it one)
  const std::size_t n_points = mine.rows.size();
  std::vector<std::pair<unsigned int, std::size_t>> first(n_points, {~0u, 0}); // rank, entry
  for (auto rank = unsigned(all_ids.size()); rank-- > 0;) // the lowest rank last: it wins
  {
    const auto& id = all_ids[rank];
    for (std::size_t e = 0; e < id.size() / 4; ++e)
      if (e == 0 || id[4 * (e - 1)] != id[4 * e]) // the first entry of a point's row
        first[id[4 * e]] = {rank, e};
  }
  ShapeRows r;
  r.rows.resize(n_points);
  std::map<types::global_dof_index, unsigned int> slot_of; // x-DoF of a node -> slot
  for (std::size_t p = 0; p < n_points; ++p)
  {
    const unsigned int rank = first[p].first;
    if (rank == ~0u)
      continue;
    const auto& id = all_ids[rank];
    const auto& value = all_values[rank];
    std::size_t end = first[p].second;
    while (end < id.size() / 4 && id[4 * end] == p)
      ++end;
    // the row's nodes by position, not by the cell's numbering: the same order whichever of the
    // cells at a face holds the point, on any number of ranks
    std::vector<std::size_t> entries(end - first[p].second);
    std::iota(entries.begin(), entries.end(), first[p].second);
    const auto position = [&](const std::size_t e) {
      return std::array<double, 3>{{value[4 * e + 1], value[4 * e + 2], value[4 * e + 3]}};
    };
    std::sort(entries.begin(), entries.end(),
              [&](const std::size_t a, const std::size_t b) { return position(a) < position(b); });
    for (const std::size_t e : entries)
    {
      auto [it, fresh] = slot_of.emplace(id[4 * e + 1], unsigned(slot_of.size()));
      if (fresh)
      {
        for (unsigned int d = 0; d < 3; ++d)
          r.slot_dofs.push_back(id[4 * e + 1 + d]);
        r.slot_points.emplace_back(value[4 * e + 1], value[4 * e + 2], value[4 * e + 3]);
      }
      r.rows[p].emplace_back(it->second, value[4 * e]);
    }
  }
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

  const ShapeRows r = shared_rows(shape_rows(fe, locator, at.size(), n_points_), comm_);
  slot_point_ = r.slot_points; // a reinit starts afresh
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

// Local-form positions of the slot DoFs this rank owns (not_owned for the others'); each slot
// DoF must have exactly one owner.
void PointTransfer::index_slot_dofs(const fem::ExplicitDynamics& fe,
                                    const std::vector<dealii::types::global_dof_index>& slot_dofs,
                                    const std::string& where)
{
  const IndexSet& owned = fe.owned_dofs();
  const auto first = owned.n_elements() > 0 ? owned.nth_index_in_set(0) : 0;
  slot_local_.clear();
  std::vector<int> owners(slot_dofs.size(), 0);
  for (std::size_t k = 0; k < slot_dofs.size(); ++k)
  {
    const bool mine = owned.is_element(slot_dofs[k]);
    slot_local_.push_back(mine ? unsigned(slot_dofs[k] - first) : not_owned);
    owners[k] = mine ? 1 : 0;
  }
  if (parallel_)
    MPI_Allreduce(MPI_IN_PLACE, owners.data(), int(owners.size()), MPI_INT, MPI_SUM, comm_);
  for (const int n : owners)
    if (n != 1)
      throw std::runtime_error(where + ": an interface node's DoF has " + std::to_string(n) +
                               " owning ranks (expected one)");
}

void PointTransfer::gather(const fem::LA::MPI::Vector& x, std::vector<double>& slots) const
{
  std::vector<double> none;
  gather(x, slots, none);
}

void PointTransfer::gather(const fem::LA::MPI::Vector& x, std::vector<double>& slots,
                           std::vector<double>& root_values) const
{
  gather_reduced(x, slots, root_values, true);
}

void PointTransfer::gather_summed(const fem::LA::MPI::Vector& x, std::vector<double>& slots,
                                  std::vector<double>& point_values) const
{
  gather_reduced(x, slots, point_values, false);
}

void PointTransfer::gather_reduced(const fem::LA::MPI::Vector& x, std::vector<double>& slots,
                                   std::vector<double>& root_values, const bool root_only) const
{
  slots.resize(slot_local_.size());
  {
    fem::LocalArray a(x);
    for (std::size_t k = 0; k < slot_local_.size(); ++k)
      slots[k] = slot_local_[k] != not_owned ? a[slot_local_[k]] : 0.0;
  }
  if (!parallel_)
    return;
  // one reduction for both: each value has one rank that gives it, the others add zeros
  // (exact), so every rank ends with the values themselves
  if (root_only && Utilities::MPI::this_mpi_process(comm_) != 0)
    std::fill(root_values.begin(), root_values.end(), 0.0);
  reduction_.assign(slots.begin(), slots.end());
  reduction_.insert(reduction_.end(), root_values.begin(), root_values.end());
  MPI_Allreduce(MPI_IN_PLACE, reduction_.data(), int(reduction_.size()), MPI_DOUBLE, MPI_SUM,
                comm_);
  std::copy(reduction_.begin(), reduction_.begin() + long(slots.size()), slots.begin());
  std::copy(reduction_.begin() + long(slots.size()), reduction_.end(), root_values.begin());
}

void PointTransfer::scatter_add(const std::vector<double>& slots, fem::LA::MPI::Vector& f) const
{
  fem::LocalArray a(f);
  for (std::size_t k = 0; k < slot_local_.size(); ++k)
    if (slot_local_[k] != not_owned)
      a[slot_local_[k]] += slots[k];
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
