#pragma once
// When an explicit run records a step and when it stops: shared by the one-process run
// (run_explicit.h) and the run on several MPI ranks (distributed/run_explicit.h), so that both
// record and stop after the same steps.
#include "dem/model/case_config.h"
#include <algorithm>

namespace dembridge::dem
{
/// Whether step @p n (1-based) records (energies, history, stop checks): every record
/// interval, the first step, the last, and every min(100, record interval) steps when a
/// quasi-static or equilibrium stop is asked for.
inline bool records_step(long n, bool at_end_time, const RunConfig& run, long record_interval)
{
  const long quasi_static_check = std::max<long>(1, std::min<long>(100, record_interval));
  return n % record_interval == 0 || n == 1 || at_end_time ||
         ((run.quasi_static_speed > 0 || run.equilibrium_ratio > 0) && n % quasi_static_check == 0);
}

/// Why the run stops after the step just taken, or nullptr to go on. The quasi-static and
/// equilibrium stops apply on recorded steps after the last load ramp and @p loads_end.
template <class Solver>
const char* stop_reason(const Solver& solver, const RunConfig& run, bool at_end_time, bool record,
                        double loads_end)
{
  if (at_end_time)
    return "end time";
  if (solver.steps() >= run.max_steps)
    return "step limit";
  if (!(record && solver.time() > solver.last_ramp_end() && solver.time() > loads_end))
    return nullptr;
  if (run.quasi_static_speed > 0 && solver.max_speed() < run.quasi_static_speed)
    return "quasi-static";
  if (run.equilibrium_ratio > 0 && solver.unbalanced_force_ratio() < run.equilibrium_ratio)
    return "equilibrium";
  return nullptr;
}
} // namespace dembridge::dem
