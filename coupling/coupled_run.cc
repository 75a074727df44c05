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

CoupledRunResult run_coupled(CoupledProblem& problem, const CoupledRunSettings& s,
                             CoupledRunObserver& observer)
{
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_progress = start, last_checkpoint = start;
  // the steps to the end time, rounded so that t_end itself is reached
  long planned =
      std::min(s.max_steps, std::max(1L, long(std::ceil(s.end_time / problem.time_step() - 1e-9))));
  const long record_every = std::max(1L, s.record_interval);

  CoupledRunProgress progress;
  progress.next_checkpoint_time = s.checkpoint_interval;
  observer.on_start(problem, progress); // a resumed run restores the state here
  const double coupling_before = problem.coupling_seconds();
  const long first = problem.steps();
  if (problem.growth_checks().planned_steps > 0) // a resumed run whose region grew
    planned = problem.growth_checks().planned_steps;
  const dem::StepRate step_rate(first, start); // a resumed run's own steps, from its start

  CoupledRunResult r;
  r.stop_reason = planned == s.max_steps ? "max steps" : "end time";
  // an adaptive region is checked at every record, and while bonds break every few steps
  const AdaptiveRegion* adaptive = problem.adaptive_region();
  auto& checks = problem.growth_checks(); // a resumed run's from the checkpoint
  long& last_check = checks.last_step;
  long& broken_at_check = checks.broken_bonds;
  auto broken_bonds = [&]
  {
    const auto* solver = problem.particle_solver();
    long n = solver ? solver->n_broken_bonds() : 0;
    if (dealii::Utilities::MPI::n_mpi_processes(problem.communicator()) > 1)
      n = dealii::Utilities::MPI::broadcast(problem.communicator(), n, 0);
    return n;
  };
  for (long n = first; n < planned; ++n)
  {
    const bool last = n + 1 == planned;
    const bool snapshot =
        n == 0 || last || (s.snapshot_interval > 0 && (n + 1) % s.snapshot_interval == 0);
    const bool crack_check = adaptive && adaptive->settings().crack_check_interval > 0 &&
                             n + 1 - last_check >= adaptive->settings().crack_check_interval &&
                             broken_bonds() > broken_at_check;
    const bool record = n == 0 || last || snapshot || crack_check || (n + 1) % record_every == 0;
    problem.step(record);
    if (record)
    {
      const auto& e = problem.energies();
      progress.max_balance_error = std::max(progress.max_balance_error, e.balance_error());
      progress.max_tie_gap = std::max(progress.max_tie_gap, problem.max_tie_gap());
      observer.on_record(problem);
      if (adaptive && !last)
      {
        last_check = n + 1;
        broken_at_check = broken_bonds();
        if (const auto event = problem.grow_region_if_due())
        {
          observer.on_region_growth(problem, *event);
          // the common step may have changed: the steps left to the end time anew
          const long left =
              long(std::ceil((s.end_time - problem.time()) / problem.time_step() - 1e-9));
          planned = std::min(s.max_steps, n + 1 + std::max(1L, left));
          checks.planned_steps = planned;
        }
      }
      bool at_rest = false;
      if (s.rest_tolerance > 0 && problem.time() >= s.rest_after)
      {
        const double kinetic = e.dem_kinetic + e.fe_kinetic;
        const double stored = kinetic + e.dem_strain + e.fe_strain;
        int& quiet = progress.quiet_records;
        quiet = stored > 0 && kinetic < s.rest_tolerance * stored ? quiet + 1 : 0;
        at_rest = quiet >= std::max(1, s.rest_records);
      }
      if (snapshot || at_rest)
        observer.on_snapshot(problem);
      if (at_rest)
      {
        r.stop_reason = "at rest";
        break;
      }
      const auto now = clock::now();
      if (std::chrono::duration<double>(now - last_progress).count() >= s.progress_seconds)
      {
        last_progress = now;
        observer.on_progress(problem, double(n + 1) / double(planned),
                             step_rate.per_second(n + 1, now),
                             step_rate.seconds_left(n + 1, planned, now));
      }
    }
    if (last)
      break;
    // Checkpoints between steps, after the step's records (as run_explicit.cc): on simulated
    // time (reproducible steps) or on wall time.
    bool checkpoint = false;
    const double dt = problem.time_step();
    if (s.checkpoint_interval > 0 && problem.time() + 0.5 * dt >= progress.next_checkpoint_time)
    {
      checkpoint = true;
      while (progress.next_checkpoint_time <= problem.time() + 0.5 * dt)
        progress.next_checkpoint_time += s.checkpoint_interval;
    }
    if (s.checkpoint_wall_interval > 0)
    {
      bool due = std::chrono::duration<double>(clock::now() - last_checkpoint).count() >=
                 s.checkpoint_wall_interval;
      // why: the ranks' clocks differ and a checkpoint is collective: rank 0's clock decides
      if (dealii::Utilities::MPI::n_mpi_processes(problem.communicator()) > 1)
        due = dealii::Utilities::MPI::broadcast(problem.communicator(), due, 0);
      checkpoint = checkpoint || due;
    }
    if (checkpoint)
    {
      observer.on_checkpoint(problem, progress);
      last_checkpoint = clock::now();
    }
    if (s.kill_after_step > 0 && problem.steps() == s.kill_after_step)
      std::raise(SIGKILL);
  }
  r.max_balance_error = progress.max_balance_error;
  r.max_tie_gap = progress.max_tie_gap;
  r.steps = problem.steps();
  r.time = problem.time();
  r.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
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
