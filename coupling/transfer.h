#pragma once
// Transfer between the FE nodes and a fixed set of points (the interface particles' reference
// centres X_p), per displacement component c:
//   interpolation  (G x)_{p,c} = sum_I N_I(xi_p) x_{I,c}     the FE field at the point
//   spreading      (G^T y)_{I,c} = sum_p N_I(xi_p) y_{p,c}   point forces to nodal forces
// xi_p are the reference coordinates of X_p in the FE cell that holds it, found once at setup:
// Utilities::MPI::RemotePointEvaluation locates every point in the distributed mesh and gives
// it one owning rank (a point on a face shared by cells of two ranks goes to one of them). The
// rows (cell, DoFs, shape values N_I(xi_p)) are then shared, so that every rank holds all of
// them as a small sparse matrix over "slots", the nodes the interface touches (numbered alike
// on every rank), and applies it with plain loops. Every rank therefore holds all point and slot
// values (the particle side lives on rank 0; the multiplier solve runs redundantly on every
// rank, multipliers.h): gathering the FE nodes' values is one MPI_Allreduce of the slot values,
// each given by the rank that owns the DoF, and it can carry rank 0's point values along;
// interpolation and spreading need no communication, and a rank adds forces to the DoFs it owns.
// RemotePointEvaluation's own per-call exchange allocates buffers on every call, which a loop
// that runs every time step must not do; the precomputed rows do not.
#include "dem/core/types.h"
#include "fem/explicit_dynamics.h"
#include <string>
#include <utility>
#include <vector>

namespace dembridge::coupling
{
class PointTransfer
{
public:
  /// Locates @p points (given on rank 0; other ranks pass none) in @p fe's mesh (collective).
  /// Throws std::runtime_error "<where>: ..." naming the first point that lies outside it.
  void reinit(const fem::ExplicitDynamics& fe, const std::vector<dem::Vec3>& points,
              const std::string& where);

  std::size_t n_points() const { return n_points_; }
  /// Nodes touched by the interface's points; slot vectors hold 3 values per slot.
  std::size_t n_slots() const { return slot_local_.size() / 3; }

  /// Slot values of an owned FE vector, on every rank (collective: one MPI_Allreduce).
  void gather(const fem::LA::MPI::Vector& x, std::vector<double>& slots) const;
  /// The same, with @p root_values (rank 0's; the other ranks' are overwritten) reaching every
  /// rank in the same reduction.
  void gather(const fem::LA::MPI::Vector& x, std::vector<double>& slots,
              std::vector<double>& root_values) const;
  /// The same, with @p point_values summed over the ranks in the same reduction: each value
  /// given by one rank (the owner of its particle), zero on the others, so that the sum is the
  /// value itself, bit for bit, on any number of ranks.
  void gather_summed(const fem::LA::MPI::Vector& x, std::vector<double>& slots,
                     std::vector<double>& point_values) const;
  /// f += the slot values at the DoFs this rank owns (every rank holds all slot values: no
  /// communication).
  void scatter_add(const std::vector<double>& slots, fem::LA::MPI::Vector& f) const;
  /// points = G slots, 3 values per point (every rank holds all rows: no communication).
  void interpolate(const std::vector<double>& slots, std::vector<double>& points) const;
  /// slots = G^T points (all points' rows: the assembled nodal values).
  void spread(const std::vector<double>& points, std::vector<double>& slots) const;

  /// Shape values of the rows: for point p, entries [row_ptr[p], row_ptr[p+1]) of (slot, N).
  const std::vector<unsigned int>& row_pointers() const { return row_ptr_; }
  const std::vector<unsigned int>& row_slots() const { return row_slot_; }
  const std::vector<double>& row_values() const { return row_value_; }
  /// Support point of each slot (node position).
  const std::vector<dealii::Point<3>>& slot_points() const { return slot_point_; }
  MPI_Comm communicator() const { return comm_; }
  bool parallel() const { return parallel_; }

private:
  /// The steps of reinit (transfer.cc): the rows (slot, N) per point stored by row and by slot;
  /// each slot DoF's place in an owned vector's local form.
  void store_rows(const std::vector<std::vector<std::pair<unsigned int, double>>>& rows,
                  std::size_t n_slots);
  void index_slot_dofs(const fem::ExplicitDynamics& fe,
                       const std::vector<dealii::types::global_dof_index>& slot_dofs,
                       const std::string& where);

  MPI_Comm comm_ = MPI_COMM_SELF;
  bool parallel_ = false;
  std::size_t n_points_ = 0;
  std::vector<unsigned int> row_ptr_, row_slot_;
  std::vector<double> row_value_;
  /// the rows by slot (spread): entries [col_ptr[s], col_ptr[s+1]) of (point, N)
  std::vector<unsigned int> col_ptr_, col_point_;
  std::vector<double> col_value_;
  /// per slot and component: the index of the DoF in this rank's owned entries, or not_owned
  static constexpr unsigned int not_owned = ~0u;
  std::vector<unsigned int> slot_local_;
  std::vector<dealii::Point<3>> slot_point_;
  mutable std::vector<double> reduction_; ///< gather's buffer (MPI)
  void gather_reduced(const fem::LA::MPI::Vector& x, std::vector<double>& slots,
                      std::vector<double>& values, bool root_only) const;
};
} // namespace dembridge::coupling
