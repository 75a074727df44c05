#pragma once
// Drives an ExplicitSolver through a case: stop criteria (end time, step limit, quasi-static
// rest), periodic records (history) and snapshots (ParaView), progress reports, and the
// measured quantities of the case (deflection of a group, natural frequency, energy balance).
#include "dem/model/case_config.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include <memory>
#include <optional>
#include <string>

namespace dembridge::dem
{
/// What the driver itself carries from step to step (beside the solver): the energy balance's
/// worst error so far, the sampled oscillation, the next checkpoint time. Part of a checkpoint.
struct RunProgress
{
  double worst_error = 0, largest_seen = 0;
  std::vector<double> frequency_time, frequency_displacement;
  double next_checkpoint_time = 0; ///< s; 0 until the first checkpoint is scheduled
  void visit_state(StateArchive& a);
};

/// Receives what the run produces; the app implements it (CSV, VTU, console).
class RunObserver
{
public:
  virtual ~RunObserver() = default;
  /// Once, before the first step, with the solver in its final form: a resumed run restores
  /// the solver's and the progress' state here (visit_state).
  virtual void on_start(ExplicitSolver&, RunProgress&) {}
  /// When a checkpoint is due (RunSchedule), between steps: save the solver's and the
  /// progress' state.
  virtual void on_checkpoint(ExplicitSolver&, RunProgress&) {}
  virtual void on_record(const ExplicitSolver&) {}   ///< energies and bond forces are fresh
  virtual void on_snapshot(const ExplicitSolver&) {} ///< likewise, at snapshot steps
  virtual void on_progress(const ExplicitSolver&, double /*fraction*/, double /*steps_per_s*/,
                           double /*eta_s*/)
  {
  }
};

struct RunSchedule
{
  long record_interval = 100;          ///< steps between history records
  long snapshot_interval = 0;          ///< steps between snapshots; 0: first and last only
  double progress_seconds = 2;         ///< wall time between progress reports
  double checkpoint_interval = 0;      ///< simulated time between checkpoints (s); 0: none
  double checkpoint_wall_interval = 0; ///< wall time between checkpoints (s); 0: none
  /// Tests of checkpoint and restart: after this step the process kills itself (SIGKILL, as
  /// `kill -9` would); 0: never.
  long kill_after_step = 0;
};

struct RunResult
{
  long steps = 0;
  long steps_made = 0; ///< by this run: a resumed run's since its checkpoint (wall_seconds' steps)
  double time = 0;
  double wall_seconds = 0;
  std::string stop_reason;
  EnergyBalance energy;
  double energy_balance_error = 0;   ///< max over the run of |balance| / largest component so far
  double unbalanced_force_ratio = 0; ///< at the last record (ExplicitSolver)
  std::optional<double> deflection;
  Vec3 deflection_vector = Vec3::Zero();
  std::optional<double> natural_frequency; ///< Hz
};

/// The explicit solver of @p model as the case configures it (time step, damping, threads), with
/// the model's step contributions (contacts, walls, ...) attached: what run_explicit steps, and
/// what a caller that steps the model itself (the Python module) steps.
std::unique_ptr<ExplicitSolver> make_explicit_solver(Model& model, const CaseConfig& config);

RunResult run_explicit(Model& model, const CaseConfig& config, RunObserver& observer,
                       const RunSchedule& schedule);

/// Frequency (Hz) of a sampled oscillation from its upward mean crossings, with linear
/// interpolation between samples; nullopt with fewer than two full periods.
std::optional<double> oscillation_frequency(const std::vector<double>& t,
                                            const std::vector<double>& u);
} // namespace dembridge::dem
