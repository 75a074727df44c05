#pragma once
// Driving a coupled DEM-FE run (coupled_problem.h) from start to stop, and what it measures.
//
// The loop steps both sides with the common time step, records every `record_interval` steps
// (energies of both sides, the tie's gap, the multiplier work), writes snapshots every
// `snapshot_interval` steps (first and last always), reports progress every few seconds and
// stops at the end time, or earlier once at rest:
//   rest: after every load ramp has ended (t >= rest_after), the kinetic share of both sides,
//         (K_DEM + K_FE) / (K_DEM + K_FE + U_DEM + U_FE), stays below `rest_tolerance` at
//         `rest_records` consecutive records. The run is damped (Coupling/mass damping) for
//         such quasi-static use; a share below the tolerance at one record can be the turning
//         point of an oscillation, several in a row cannot (a period spans many records).
// Adaptive particle region: after each record the region may grow (CoupledProblem::
// grow_region_if_due); the observer hears of it, and the steps left are counted anew with the
// common step the grown problem has.
// Measurements at the end (every rank holds them): the energies, the largest energy balance
// error over the records (coupled_problem.h), and for a pulse started on one side
// (measurements.h) the share of the initial energy left on that side (reflected) and on the
// other (transmitted) once it has crossed the band.
// Units: SI (s, J, m).
#include "coupling/coupled_problem.h"
#include <string>

namespace dembridge::coupling
{
struct CoupledRunSettings
{
  double end_time = 0;            ///< s
  long max_steps = 100000000;     ///< a cap on the steps
  long record_interval = 100;     ///< steps between records
  long snapshot_interval = 0;     ///< steps between snapshots; 0: first and last only
  double rest_tolerance = 0;      ///< kinetic share; 0: run to the end time
  int rest_records = 5;           ///< consecutive records below the tolerance
  double rest_after = 0;          ///< s: the end of the last load ramp
  double progress_seconds = 2;    ///< wall time between progress reports
  int pulse_side = 0;             ///< +1: a pulse starts in the continuum, -1: in the particles
  double checkpoint_interval = 0; ///< simulated time between checkpoints (s); 0: none
  double checkpoint_wall_interval = 0; ///< wall time between checkpoints (s); 0: none
  /// Tests of checkpoint and restart: after this step the process kills itself (SIGKILL, as
  /// `kill -9` would); 0: never.
  long kill_after_step = 0;
};

/// What the loop carries from step to step beside the problem: the measured maxima, the rest
/// criterion's count, the next checkpoint time. Part of a checkpoint (group /run/).
struct CoupledRunProgress
{
  double max_balance_error = 0, max_tie_gap = 0;
  int quiet_records = 0;
  double next_checkpoint_time = 0; ///< s
  void visit_state(dem::StateArchive& a);
};

/// The caller's hooks (output files, progress lines); every rank is called.
class CoupledRunObserver
{
public:
  virtual ~CoupledRunObserver() = default;
  /// Once, before the first step: a resumed run restores the problem's and the progress' state
  /// here (their visit_state).
  virtual void on_start(CoupledProblem&, CoupledRunProgress&) {}
  /// When a checkpoint is due (CoupledRunSettings), between steps, after the step's records.
  virtual void on_checkpoint(CoupledProblem&, CoupledRunProgress&) {}
  virtual void on_record(const CoupledProblem&) {}
  virtual void on_snapshot(CoupledProblem&) {}
  /// After the adaptive particle region grew (between steps, after the record that asked for
  /// it): the problem's particles, bonds and continuum are new objects.
  virtual void on_region_growth(CoupledProblem&, const GrowthEvent&) {}
  virtual void on_progress(const CoupledProblem&, double /*fraction*/, double /*steps_per_s*/,
                           double /*eta_s*/)
  {
  }
};

struct CoupledRunResult
{
  long steps = 0;
  double time = 0;              ///< s
  std::string stop_reason;      ///< "end time", "at rest", "max steps"
  double wall_seconds = 0;      ///< the loop
  double coupling_seconds = 0;  ///< of which the continuum, transfers and multipliers
  double max_balance_error = 0; ///< largest balance error over the records
  double max_tie_gap = 0;       ///< m, largest over the records
  CoupledProblem::Energies energies;
  double reflected_energy_ratio = -1;   ///< pulse runs: energy left on the starting side / E_0
  double transmitted_energy_ratio = -1; ///< ... on the other side / E_0
};

/// Runs @p problem (set up, initial state given) to its stop; collective.
CoupledRunResult run_coupled(CoupledProblem& problem, const CoupledRunSettings& settings,
                             CoupledRunObserver& observer);
} // namespace dembridge::coupling
