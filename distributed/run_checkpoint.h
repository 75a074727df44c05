#pragma once
// Checkpoints of a DEM run on several MPI ranks (docs/parallel.md, "Checkpoints"). Rank 0 writes
// the whole run in the one-rank layout (app/checkpoint, dem/core/state_archive.h) from its model
// and its report solver, into which DistributedSolver::gather_for_checkpoint puts every
// particle, every bond, the support reactions and the running sums over the ranks. The contacts'
// one-rank state is a neighbour list over one store's indices, which no rank has: in its place
// the report solver carries a ContactCheckpoint, whose state is every contact's history by
// global ids (ContactForces::export_history's records of every rank, one copy each) and the
// model's ContactForces holding the contact sums over the ranks (sum_contact_state). A resume
// reads the file on every rank into the whole model and spreads it as at the setup; rank 0's
// solver continues the sums, the other ranks start theirs at zero (the sums are linear).
#include "dem/contacts/contact_forces.h"
#include "dem/core/state_archive.h"
#include "dem/solvers/step_contribution.h"
#include <deal.II/base/mpi.h>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace dembridge::distributed
{
/// A StateArchive in memory by path ("contacts/energy/stored"): a visit saved into it can be
/// changed field by field and then restored from it (start_loading).
class FieldArchive : public dem::StateArchive
{
public:
  using Value =
      std::variant<std::vector<double>, std::vector<std::int32_t>, std::vector<std::int64_t>,
                   std::vector<std::uint8_t>, std::vector<std::uint32_t>, std::vector<dem::Vec3>,
                   std::vector<dem::Quat>, std::string>;
  bool loading() const override { return loading_; }
  void start_loading() { loading_ = true; }
  void enter(const std::string& group) override { path_.push_back(group); }
  void leave() override { path_.pop_back(); }
  std::string where() const override;
  void io(const std::string& n, std::vector<double>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<std::int32_t>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<std::int64_t>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<std::uint8_t>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<std::uint32_t>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<dem::Vec3>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<dem::Quat>& v) override { field(n, v); }
  void io(const std::string& n, std::string& text) override { field(n, text); }
  std::map<std::string, Value>& fields() { return fields_; }

private:
  template <class T> void field(const std::string& name, T& v)
  {
    const std::string key = where() + name;
    if (!loading_)
    {
      fields_[key] = v;
      return;
    }
    const auto at = fields_.find(key);
    if (at == fields_.end() || !std::holds_alternative<T>(at->second))
      throw std::logic_error(key + ": not saved in this FieldArchive");
    v = std::get<T>(at->second);
  }
  bool loading_ = false;
  std::vector<std::string> path_;
  std::map<std::string, Value> fields_;
};

/// Stands for the contacts in rank 0's report solver, which is never stepped: in a checkpoint,
/// the contact histories of the whole run and @p whole (the model's contacts, with the sums).
class ContactCheckpoint : public dem::StepContribution
{
public:
  /// @p one_rank_layout: a resume reads a checkpoint written on one rank, where this
  /// contribution's place holds @p whole's own state (the contacts over the model's indices, which
  /// are the global ids), and takes the histories from it.
  explicit ContactCheckpoint(dem::ContactForces& whole, bool one_rank_layout = false)
      : whole_(whole), one_rank_layout_(one_rank_layout)
  {
  }
  void add_forces(dem::ParticleStore&, double, double, bool) override {}
  bool checkpointable() const override { return true; }
  void visit_state(dem::StateArchive& a) override;
  /// ContactForces::history_record_size doubles a contact, sorted by its key, one copy each.
  std::vector<double>& history() { return history_; }

private:
  dem::ContactForces& whole_;
  bool one_rank_layout_;
  std::vector<double> history_;
};

/// Collective: @p whole (rank 0's; ignored elsewhere) takes the running sums of every rank's
/// @p rank added in rank order (energies, the walls' forces, counts) and rank 0's walls'
/// positions.
void sum_contact_state(dem::ContactForces& rank, dem::ContactForces* whole, MPI_Comm comm);

/// A rank other than 0 continuing a restored run: its contacts' running sums start at zero.
void zero_contact_sums(dem::ContactForces& contacts);

/// Collective: every rank's @p mine, concatenated in rank order on rank 0 (empty elsewhere).
std::vector<double> gather_on_root(const std::vector<double>& mine, MPI_Comm comm);

/// Collective: every rank's contact histories (@p mine), one copy of each contact, sorted by key,
/// on rank 0 (empty elsewhere).
std::vector<double> gather_contact_history(const std::vector<double>& mine, MPI_Comm comm);
} // namespace dembridge::distributed
