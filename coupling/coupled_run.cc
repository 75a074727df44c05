#include "coupling/coupled_run.h"
#include "dem/core/progress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <deal.II/base/mpi.h>
#include <stdexcept>

namespace dembridge::coupling
{
void CoupledRunProgress::visit_state(dem::StateArchive& a)
{
  dem::StateGroup group(a, "run");
  a.io("max_balance_error", max_balance_error);
  a.io("max_tie_gap", max_tie_gap);
  a.io("quiet_records", quiet_records);
  a.io("next_checkpoint_time", next_checkpoint_time);
}

namespace
{
using Clock = std::chrono::steady_clock;

/// The loop of run_coupled: its state between steps (the planned steps, the clocks of the
/// progress reports and checkpoints) and what it decides after each step.
class CoupledLoop
{
public:
  CoupledLoop(CoupledProblem& problem, const CoupledRunSettings& s, CoupledRunObserver& observer,
              CoupledRunProgress& progress, Clock::time_point start, long planned)
      : problem_(problem), s_(s), observer_(observer), progress_(progress), last_progress_(start),
        last_checkpoint_(start), planned_(planned), record_every_(std::max(1L, s.record_interval)),
        step_rate_(problem.steps(), start), adaptive_(problem.adaptive_region()),
        checks_(problem.growth_checks())
  {
  }
  /// Steps from the problem's step count to the planned last step; true when it stopped early,
  /// at rest.
  bool run();

private:
  long broken_bonds() const;
  /// An adaptive region is checked at every record, and while bonds break every few steps.
  bool crack_check_due(long n) const;
  /// After the record of step n: growth, the rest criterion, snapshot and progress; true when
  /// at rest.
  bool after_record(long n, bool last, bool snapshot);
  void grow_if_due(long n);
  bool at_rest();
  void report_progress(long n);
  void checkpoint_if_due();

  CoupledProblem& problem_;
  const CoupledRunSettings& s_;
  CoupledRunObserver& observer_;
  CoupledRunProgress& progress_;
  Clock::time_point last_progress_, last_checkpoint_;
  long planned_;
  const long record_every_;
  const dem::StepRate step_rate_; // a resumed run's own steps, from its start
  const AdaptiveRegion* adaptive_;
  CoupledProblem::GrowthChecks& checks_; // a resumed run's from the checkpoint
};

bool CoupledLoop::run()
{
  for (long n = problem_.steps(); n < planned_; ++n)
  {
    const bool last = n + 1 == planned_;
    const bool snapshot =
        n == 0 || last || (s_.snapshot_interval > 0 && (n + 1) % s_.snapshot_interval == 0);
    const bool crack_check = crack_check_due(n);
    const bool record = n == 0 || last || snapshot || crack_check || (n + 1) % record_every_ == 0;
    problem_.step(record);
    if (record && after_record(n, last, snapshot))
      return true;
    if (last)
      break;
    checkpoint_if_due();
    if (s_.kill_after_step > 0 && problem_.steps() == s_.kill_after_step)
      std::raise(SIGKILL);
  }
  return false;
}

long CoupledLoop::broken_bonds() const
{
  const auto* solver = problem_.particle_solver();
  long n = solver ? solver->n_broken_bonds() : 0;
  if (dealii::Utilities::MPI::n_mpi_processes(problem_.communicator()) > 1)
    n = dealii::Utilities::MPI::broadcast(problem_.communicator(), n, 0);
  return n;
}

bool CoupledLoop::crack_check_due(const long n) const
{
  return adaptive_ && adaptive_->settings().crack_check_interval > 0 &&
         n + 1 - checks_.last_step >= adaptive_->settings().crack_check_interval &&
         broken_bonds() > checks_.broken_bonds;
}

bool CoupledLoop::after_record(const long n, const bool last, const bool snapshot)
{
  const auto& e = problem_.energies();
  progress_.max_balance_error = std::max(progress_.max_balance_error, e.balance_error());
  progress_.max_tie_gap = std::max(progress_.max_tie_gap, problem_.max_tie_gap());
  observer_.on_record(problem_);
  if (adaptive_ && !last)
    grow_if_due(n);
  const bool rest = at_rest();
  if (snapshot || rest)
  {
    problem_.gather_particles(); // the particles on the ranks: rank 0's model takes them all
    observer_.on_snapshot(problem_);
  }
  if (rest)
    return true;
  report_progress(n);
  return false;
}

void CoupledLoop::grow_if_due(const long n)
{
  checks_.last_step = n + 1;
  checks_.broken_bonds = broken_bonds();
  if (const auto event = problem_.grow_region_if_due())
  {
    observer_.on_region_growth(problem_, *event);
    // the common step may have changed: the steps left to the end time anew
    const long left =
        long(std::ceil((s_.end_time - problem_.time()) / problem_.time_step() - 1e-9));
    planned_ = std::min(s_.max_steps, n + 1 + std::max(1L, left));
    checks_.planned_steps = planned_;
  }
}

// At rest: after the last ramp, the kinetic share below the tolerance at enough records in a
// row (coupled_run.h).
bool CoupledLoop::at_rest()
{
  if (!(s_.rest_tolerance > 0 && problem_.time() >= s_.rest_after))
    return false;
  const auto& e = problem_.energies();
  const double kinetic = e.dem_kinetic + e.fe_kinetic;
  const double stored = kinetic + e.dem_strain + e.fe_strain;
  int& quiet = progress_.quiet_records;
  quiet = stored > 0 && kinetic < s_.rest_tolerance * stored ? quiet + 1 : 0;
  return quiet >= std::max(1, s_.rest_records);
}

void CoupledLoop::report_progress(const long n)
{
  const auto now = Clock::now();
  if (std::chrono::duration<double>(now - last_progress_).count() >= s_.progress_seconds)
  {
    last_progress_ = now;
    observer_.on_progress(problem_, double(n + 1) / double(planned_),
                          step_rate_.per_second(n + 1, now),
                          step_rate_.seconds_left(n + 1, planned_, now));
  }
}

// Checkpoints between steps, after the step's records (as run_explicit.cc): on simulated time
// (reproducible steps) or on wall time.
void CoupledLoop::checkpoint_if_due()
{
  bool checkpoint = false;
  const double dt = problem_.time_step();
  if (s_.checkpoint_interval > 0 && problem_.time() + 0.5 * dt >= progress_.next_checkpoint_time)
  {
    checkpoint = true;
    while (progress_.next_checkpoint_time <= problem_.time() + 0.5 * dt)
      progress_.next_checkpoint_time += s_.checkpoint_interval;
  }
  if (s_.checkpoint_wall_interval > 0)
  {
    bool due = std::chrono::duration<double>(Clock::now() - last_checkpoint_).count() >=
               s_.checkpoint_wall_interval;
    // why: the ranks' clocks differ and a checkpoint is collective: rank 0's clock decides
    if (dealii::Utilities::MPI::n_mpi_processes(problem_.communicator()) > 1)
      due = dealii::Utilities::MPI::broadcast(problem_.communicator(), due, 0);
    checkpoint = checkpoint || due;
  }
  if (checkpoint)
  {
    observer_.on_checkpoint(problem_, progress_);
    last_checkpoint_ = Clock::now();
  }
}
} // namespace

CoupledRunResult run_coupled(CoupledProblem& problem, const CoupledRunSettings& s,
                             CoupledRunObserver& observer)
{
  const auto start = Clock::now();
  // the steps to the end time, rounded so that t_end itself is reached
  long planned =
      std::min(s.max_steps, std::max(1L, long(std::ceil(s.end_time / problem.time_step() - 1e-9))));
  CoupledRunProgress progress;
  progress.next_checkpoint_time = s.checkpoint_interval;
  observer.on_start(problem, progress); // a resumed run restores the state here
  const double coupling_before = problem.coupling_seconds();
  if (problem.growth_checks().planned_steps > 0) // a resumed run whose region grew
    planned = problem.growth_checks().planned_steps;

  CoupledRunResult r;
  r.stop_reason = planned == s.max_steps ? "max steps" : "end time";
  CoupledLoop loop(problem, s, observer, progress, start, planned);
  if (loop.run())
    r.stop_reason = "at rest";
  r.max_balance_error = progress.max_balance_error;
  r.max_tie_gap = progress.max_tie_gap;
  r.steps = problem.steps();
  r.time = problem.time();
  r.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  r.coupling_seconds = problem.coupling_seconds() - coupling_before;
  r.energies = problem.energies();
  if (s.pulse_side != 0 && r.energies.initial > 0)
  {
    const double dem = r.energies.dem_total(), fe = r.energies.fe_total();
    r.reflected_energy_ratio = (s.pulse_side > 0 ? fe : dem) / r.energies.initial;
    r.transmitted_energy_ratio = (s.pulse_side > 0 ? dem : fe) / r.energies.initial;
  }
  return r;
}
} // namespace dembridge::coupling
