#pragma once
// dem/'s explicit solver on a model spread over MPI ranks (distributed_particles.h). Each rank
// steps one ExplicitSolver over its own particles and ghosts (SolverSettings::owned_particles:
// it integrates the owned ones, and books a bond held by two ranks on the rank of its end a),
// refreshes the ghosts after the step, and when particles may have changed ranks rebuilds its
// stores and a new local solver that continues the old one's running state (time, energy sums,
// crack log) and support reactions. Groups keep their members on the rank that owns them; a
// force or moment load shared by a group's members gives each rank its members' share.
//
// On record steps the figures of the step are summed over the ranks in rank order (energies,
// the unbalanced-force ratio's parts; the largest speed is the largest), so that every rank
// takes the same decisions (stop criteria) and a run's figures do not depend on message timing.
// Rank 0 keeps the whole model (the setup is replicated: every rank builds the same model and
// keeps its part) and a second ExplicitSolver over it that is never stepped: gather() puts the
// particles' state into rank 0's model, and the summed figures and the crack log into that
// solver, so that a run's observer (history, ParaView files) and measurements read them as on
// one rank. A checkpoint is that solver's state after gather_for_checkpoint (the whole run,
// run_checkpoint.h); a resume restores it into the whole model on every rank before the
// particles are spread.
#include "dem/contacts/contact_forces.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include "distributed/distributed_particles.h"
#include "distributed/run_checkpoint.h"
#include <functional>
#include <memory>
#include <unordered_map>

namespace dembridge::distributed
{
class DistributedSolver
{
public:
  /// Restores a run from a checkpoint into the whole model and the solver over it (the report
  /// solver; run_checkpoint.h) before the particles are spread.
  using Restore = std::function<void(dem::ExplicitSolver& whole)>;
  /// Every rank passes the same model and settings; @p grid is the background mesh
  /// (background_grid_for(model) by default). @p restore: called on rank 0 (its observer's
  /// on_start) and, with @p resume, on every rank: the ranks then continue the restored run,
  /// each from its part of the restored model, rank 0 with the running sums.
  DistributedSolver(dem::Model& model, const dem::SolverSettings& settings, MPI_Comm comm,
                    const BackgroundGrid* grid = nullptr, const Restore& restore = {},
                    bool resume = false, bool one_rank_contacts = false);

  /// One step on every rank (collective): the local step, the ghosts' refresh, a migration
  /// when due (or a throw on every rank when some rank became unstable); on record steps the
  /// figures summed over the ranks.
  void step(bool record = false);
  /// Collective: sums the figures of the last record (and the energy accumulators and the
  /// contact figures as they stand) over the ranks; step() does this on record steps.
  void reduce();
  /// Collective: rank 0's model takes the particles' state (every particle with @p all, else
  /// those in a group) and with @p all the state of the bonds that are no longer intact; rank
  /// 0's report solver takes the summed figures and the cracks so far.
  void gather(bool all);
  /// Collective, before a checkpoint: as gather(true), and rank 0's model and report solver take
  /// every bond's state, the support reactions, the running sums over the ranks (the contacts'
  /// too) and every contact's history: what the one-rank checkpoint of the report solver holds.
  void gather_for_checkpoint();
  /// Collective, before the ranks write their particles (a snapshot in pieces): the ghosts take
  /// their owners' reference positions, which the per-step exchange does not carry and the
  /// stress of an owned particle reads (its bonds' displacements, particle_stress.h).
  void share_ghost_references();

  double time() const { return local_->time(); }
  long steps() const { return local_->steps(); }
  double time_step() const { return local_->time_step(); }
  /// Summed over the ranks at the last record (reduce).
  const dem::EnergyBalance& energy() const { return energy_; }
  double max_speed() const { return max_speed_; }
  double unbalanced_force_ratio() const { return unbalanced_ratio_; }
  long n_broken_bonds() const { return n_broken_; }
  double last_ramp_end() const { return local_->last_ramp_end(); }
  /// Collective: the group's mean displacement over every rank.
  dem::Vec3 group_mean_displacement(int group);

  /// Rank 0: the solver over the whole model that reports the gathered state; null elsewhere.
  dem::ExplicitSolver* report() { return report_.get(); }
  DistributedParticles& particles() { return particles_; }
  const dem::ExplicitSolver& local() const { return *local_; }
  long n_migrations() const { return particles_.n_rebuilds(); }
  /// Wall seconds this rank spent in each part of its steps so far.
  struct Timings
  {
    double local_step = 0, ghosts = 0, motion_checks = 0, rebuilds = 0, records = 0;
  };
  const Timings& timings() const { return timings_; }

private:
  /// The initializer's step between the report solver and the particles: attaches the contacts'
  /// checkpoint to the report solver, restores (restore), and gives the background mesh.
  BackgroundGrid restore_whole(const BackgroundGrid* grid, const Restore& restore, bool resume,
                               bool one_rank_contacts);
  /// A resumed run's local solver, its support reactions and the figures of the checkpoint.
  void continue_restored_run();
  /// Collective: the gathered bond states into rank 0's model; @p every_bond: intact ones too.
  void gather_bond_states(bool every_bond);
  void build_local_solver(dem::ExplicitSolver::RunningState&& state);
  void migrate();
  /// Collective: the support reaction of each load a pressure follows (its ratio load) summed
  /// over the ranks in rank order, into the local solver: each rank holds only its members.
  void share_group_reactions();
  /// Collective: rank 0's model's contacts take the figures of the step at @p time summed over
  /// the ranks.
  void reduce_contacts(double time);

  dem::Model& model_;
  MPI_Comm comm_;
  bool root_;
  unsigned n_ranks_;
  dem::SolverSettings settings_;
  // (before report_ and particles_: restore_whole sets them)
  dem::ContactForces* report_contacts_ = nullptr; ///< the model's contacts (rank 0: the sums)
  std::unique_ptr<ContactCheckpoint> contact_checkpoint_;
  bool resumed_ = false;
  /// rank 0 (every rank while a resumed run is spread): built before the particles are spread
  /// (it puts the model's bonds in its order)
  std::unique_ptr<dem::ExplicitSolver> report_;
  DistributedParticles particles_;
  std::vector<std::size_t> group_sizes_; ///< members over all ranks
  std::unique_ptr<dem::ExplicitSolver> local_;
  /// the rank's contacts (a copy of the model's, stepped by the local solvers one after the
  /// other: its energy sums and wall forces run on), the model's (rank 0: reports the sums),
  /// and the contact histories that travel at a migration
  std::unique_ptr<dem::ContactForces> contacts_;
  std::vector<double> contact_history_, contact_figures_, contact_figures_all_;
  double last_step_time_ = 0; ///< t_n of the last step (its contact figures are at t_n)
  dem::EnergyBalance energy_;
  double max_speed_ = 0, unbalanced_ratio_ = 0;
  dem::ExplicitSolver::UnbalancedParts unbalanced_;
  long n_broken_ = 0;
  std::array<long, 2> broken_by_mode_{};
  std::size_t cracks_gathered_ = 0; ///< of the local crack log
  std::vector<double> reduce_buffer_;
  /// the loads a pressure's ratio follows, and their reactions over the ranks (NaN: none yet)
  std::vector<int> followed_loads_;
  std::vector<double> followed_reactions_, followed_buffer_;
  Timings timings_;
  /// rank 0: the model's bond index of each pair of global ids, and user id -> global id
  std::unordered_map<std::uint64_t, std::size_t> bond_index_;
  std::vector<std::int64_t> global_of_user_;
};

} // namespace dembridge::distributed
