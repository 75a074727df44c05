#include "dem/solvers/run_explicit.h"
#include "dem/core/progress.h"
#include "dem/solvers/run_stop.h"
#include <chrono>
#include <cmath>
#include <csignal>
#include <numeric>

namespace dembridge::dem
{
void RunProgress::visit_state(StateArchive& a)
{
  StateGroup group(a, "run");
  a.io("worst_error", worst_error);
  a.io("largest_seen", largest_seen);
  a.io("frequency_time", frequency_time);
  a.io("frequency_displacement", frequency_displacement);
  a.io("next_checkpoint_time", next_checkpoint_time);
  if (a.loading() && frequency_time.size() != frequency_displacement.size())
    throw InputError(a.where() + "frequency_time: not as long as 'frequency_displacement'");
}

std::optional<double> oscillation_frequency(const std::vector<double>& t,
                                            const std::vector<double>& u)
{
  if (u.size() < 4)
    return std::nullopt;
  const double mean = std::accumulate(u.begin(), u.end(), 0.0) / double(u.size());
  std::vector<double> crossings;
  for (std::size_t k = 1; k < u.size(); ++k)
  {
    const double a = u[k - 1] - mean, b = u[k] - mean;
    if (a < 0 && b >= 0)
      crossings.push_back(t[k - 1] + (t[k] - t[k - 1]) * (-a) / (b - a));
  }
  if (crossings.size() < 3)
    return std::nullopt;
  // Whole periods only, so the mean of the window is not biased by a partial period.
  return double(crossings.size() - 1) / (crossings.back() - crossings.front());
}

std::unique_ptr<ExplicitSolver> make_explicit_solver(Model& model, const CaseConfig& c)
{
  auto solver = std::make_unique<ExplicitSolver>(
      model.particles, model.bonds, model.groups, model.constraints, model.loads,
      SolverSettings{model.time_step, c.run.particle_damping, c.run.threads, c.run.mass_damping});
  for (const auto& contribution : model.contributions)
    solver->add_contribution(contribution.get());
  return solver;
}

RunResult run_explicit(Model& model, const CaseConfig& c, RunObserver& observer,
                       const RunSchedule& sched)
{
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const std::unique_ptr<ExplicitSolver> solver_owner = make_explicit_solver(model, c);
  ExplicitSolver& solver = *solver_owner;
  RunResult res;
  const int deflection_group =
      c.measure.deflection_group.empty()
          ? -1
          : model.group_index(c.measure.deflection_group, "Measurements/deflection group");
  const int frequency_group =
      c.measure.frequency_group.empty()
          ? -1
          : model.group_index(c.measure.frequency_group, "Measurements/frequency group");
  const Vec3 dir = c.measure.deflection_direction.normalized();
  double loads_end = 0; // free vibration starts when every finite load has ended
  for (const auto& l : model.loads)
    if (std::isfinite(l.end_time))
      loads_end = std::max(loads_end, l.end_time);
  RunProgress progress;
  progress.next_checkpoint_time = sched.checkpoint_interval;
  observer.on_start(solver, progress);             // a resumed run restores the state here
  const StepRate step_rate(solver.steps(), start); // a resumed run's own steps, from its start
  std::vector<double>& ft = progress.frequency_time;
  std::vector<double>& fu = progress.frequency_displacement;
  const long expected = long(std::min(double(c.run.max_steps), c.run.end_time / model.time_step));
  if (frequency_group >= 0)
  {
    ft.reserve(std::size_t(std::max(0L, expected)) + 2);
    fu.reserve(ft.capacity());
  }

  double& worst_error = progress.worst_error;
  double& largest_seen = progress.largest_seen;
  auto track_energy = [&](const ExplicitSolver& s)
  {
    largest_seen = std::max(largest_seen, s.energy().largest());
    if (largest_seen > 0)
      worst_error = std::max(worst_error, s.energy().error() / largest_seen);
  };
  auto last_checkpoint = start;

  // State at t = 0: one recording evaluation without advancing is not possible with a
  // leapfrog state, so the first record is after step 1.
  auto last_progress = start;
  res.stop_reason = "end time";
  while (true)
  {
    const long n = solver.steps() + 1;
    const bool at_end_time = solver.time() + 0.5 * model.time_step >= c.run.end_time;
    const bool record = records_step(n, at_end_time, c.run, sched.record_interval);
    solver.step(record);
    if (frequency_group >= 0 && solver.time() >= loads_end)
    {
      ft.push_back(solver.time());
      fu.push_back(solver.group_mean_displacement(frequency_group).dot(dir));
    }
    const char* reason = stop_reason(solver, c.run, at_end_time, record, loads_end);
    const bool stop = reason != nullptr;
    if (stop)
      res.stop_reason = reason;
    if (record)
    {
      track_energy(solver);
      if (n % sched.record_interval == 0 || n == 1 || stop)
        observer.on_record(solver);
      if (n == 1 || stop || (sched.snapshot_interval > 0 && n % sched.snapshot_interval == 0))
        observer.on_snapshot(solver);
    }
    if (!std::isfinite(solver.energy().damping) || !std::isfinite(solver.energy().external))
      throw std::runtime_error("the simulation became unstable at step " +
                               std::to_string(solver.steps()) +
                               " (t = " + std::to_string(solver.time()) + " s): non-finite energy");
    const auto now = clock::now();
    if (std::chrono::duration<double>(now - last_progress).count() > sched.progress_seconds)
    {
      last_progress = now;
      const double frac = std::min(1.0, solver.time() / c.run.end_time);
      observer.on_progress(solver, frac, step_rate.per_second(solver.steps(), now),
                           step_rate.seconds_left(solver.steps(), expected, now));
    }
    if (stop)
      break;
    // Checkpoints between steps, after the step's records: on simulated time (reproducible
    // steps) or on wall time.
    bool checkpoint = false;
    if (sched.checkpoint_interval > 0 &&
        solver.time() + 0.5 * model.time_step >= progress.next_checkpoint_time)
    {
      checkpoint = true;
      while (progress.next_checkpoint_time <= solver.time() + 0.5 * model.time_step)
        progress.next_checkpoint_time += sched.checkpoint_interval;
    }
    if (sched.checkpoint_wall_interval > 0 &&
        std::chrono::duration<double>(now - last_checkpoint).count() >=
            sched.checkpoint_wall_interval)
      checkpoint = true;
    if (checkpoint)
    {
      observer.on_checkpoint(solver, progress);
      last_checkpoint = clock::now();
    }
    if (sched.kill_after_step > 0 && solver.steps() == sched.kill_after_step)
      std::raise(SIGKILL);
  }
  res.steps = solver.steps();
  res.steps_made = step_rate.steps_made(solver.steps());
  res.time = solver.time();
  res.energy = solver.energy();
  res.energy_balance_error = worst_error;
  res.unbalanced_force_ratio = solver.unbalanced_force_ratio();
  if (deflection_group >= 0)
  {
    res.deflection_vector = solver.group_mean_displacement(deflection_group);
    res.deflection = res.deflection_vector.dot(dir);
  }
  if (frequency_group >= 0)
    res.natural_frequency = oscillation_frequency(ft, fu);
  res.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  return res;
}
} // namespace dembridge::dem
