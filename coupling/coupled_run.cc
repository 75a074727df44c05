#include "coupling/coupled_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace dembridge::coupling
{
CoupledRunResult run_coupled(CoupledProblem& problem, const CoupledRunSettings& s,
                             CoupledRunObserver& observer)
{
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_progress = start;
  const double dt = problem.time_step();
  // the steps to the end time, rounded so that t_end itself is reached
  const long planned =
      std::min(s.max_steps, std::max(1L, long(std::ceil(s.end_time / dt - 1e-9))));
  const long record_every = std::max(1L, s.record_interval);
  const double coupling_before = problem.coupling_seconds();

  CoupledRunResult r;
  r.stop_reason = planned == s.max_steps ? "max steps" : "end time";
  int quiet_records = 0;
  for (long n = 0; n < planned; ++n)
  {
    const bool last = n + 1 == planned;
    const bool snapshot =
        n == 0 || last || (s.snapshot_interval > 0 && (n + 1) % s.snapshot_interval == 0);
    const bool record = n == 0 || last || snapshot || (n + 1) % record_every == 0;
    problem.step(record);
    if (!record)
      continue;
    const auto& e = problem.energies();
    r.max_balance_error = std::max(r.max_balance_error, e.balance_error());
    r.max_tie_gap = std::max(r.max_tie_gap, problem.max_tie_gap());
    observer.on_record(problem);
    bool at_rest = false;
    if (s.rest_tolerance > 0 && problem.time() >= s.rest_after)
    {
      const double kinetic = e.dem_kinetic + e.fe_kinetic;
      const double stored = kinetic + e.dem_strain + e.fe_strain;
      quiet_records = stored > 0 && kinetic < s.rest_tolerance * stored ? quiet_records + 1 : 0;
      at_rest = quiet_records >= std::max(1, s.rest_records);
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
      const double elapsed = std::chrono::duration<double>(now - start).count();
      const double rate = double(n + 1) / elapsed;
      observer.on_progress(problem, double(n + 1) / double(planned), rate,
                           double(planned - n - 1) / rate);
    }
  }
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
