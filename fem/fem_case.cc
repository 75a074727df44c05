// dembridge::fem — run a FEM case from parsed parameters and measure it; the caller writes the
// files (fem_case.h).
#include "fem_case.h"

#include "elastic_problem.h"
#include "explicit_dynamics.h"
#include "parameters.h"
#include "reaction_measurement.h"

#include "dem/core/running_series.h"
#include "dem/core/state_archive.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <sstream>

namespace dembridge::fem
{
using namespace dealii;

void declare_parameters(ParameterHandler& prm)
{
  declare_fem_parameters(prm);
}

namespace
{
/// deal.II's timer table as text (rank 0; empty elsewhere): the caller writes it where it
/// keeps logs, not to the terminal.
std::string timing_table(const TimerOutput& timer, MPI_Comm comm)
{
  const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
  std::ostringstream table;
  std::streambuf* terminal = std::cout.rdbuf();
  if (root)
    std::cout.rdbuf(table.rdbuf());
  try
  {
    timer.print_wall_time_statistics(comm);
  }
  catch (...)
  {
    std::cout.rdbuf(terminal);
    throw;
  }
  std::cout.rdbuf(terminal);
  return table.str();
}

/// Assembles and solves the static problem, saying what runs (assembly and the AMG solve of a
/// large mesh take minutes); the solver's iterations.
unsigned int solve_static(ElasticProblem& problem, MPI_Comm comm)
{
  ConditionalOStream pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0);
  problem.make_grid();
  problem.setup_system();
  pcout << "FEM static: " << problem.n_cells() << " cells, " << problem.n_dofs() << " dofs"
        << std::endl;
  if (const std::string free = problem.free_rigid_body_modes(); !free.empty())
    throw std::runtime_error("FEM/Boundary conditions: the supports leave rigid-body modes free (" +
                             free +
                             "), so the static problem has no unique solution; hold "
                             "more components (e.g. 'points = X,Y,Z: xyz')");
  Timer phase;
  pcout << "FEM static: assembling ..." << std::endl;
  problem.assemble_system(/*condense=*/true);
  pcout << "FEM static: assembled in " << phase.wall_time() << " s; solving (CG + BoomerAMG) ..."
        << std::endl;
  phase.restart();
  const unsigned int iterations = problem.solve();
  pcout << "FEM static: CG + BoomerAMG converged in " << iterations << " iterations, "
        << phase.wall_time() << " s" << std::endl;
  return iterations;
}

/// The deflection, reactions and mean displacements FEM/Measurements asks for.
void measure_static(ElasticProblem& problem, const Parameters& p, nlohmann::json& summary)
{
  if (!p.deflection_points.empty())
  {
    const std::string where = "FEM/Measurements/deflection points";
    double mean = 0;
    std::vector<double> values;
    for (const auto& x : p.deflection_points)
    {
      values.push_back(problem.probe_value(problem.make_probe(x, where), p.deflection_direction));
      mean += values.back() / p.deflection_points.size();
    }
    summary[p.deflection_name] = mean;
    summary[p.deflection_name + "_points"] = values;
  }
  if (const auto m = measure_reaction(problem, p))
  {
    summary["reaction_force"] = m->reaction_along;
    summary["reaction_force_vector"] = {m->reaction[0], m->reaction[1], m->reaction[2]};
    if (m->has_loaded_boundary)
    {
      summary["area"] = m->area;
      summary["gauge_length"] = m->gauge_length;
      summary["elongation"] = m->elongation;
      summary["youngs_modulus"] = m->youngs_modulus;
    }
  }
  for (const auto& name : p.reaction_boundaries)
  {
    const Tensor<1, 3> r = problem.reaction(
        find_boundary(problem.boundary_names(), name, "FEM/Measurements/reaction boundaries"));
    summary["reactions"][name] = {r[0], r[1], r[2]};
  }
  for (const auto& group : p.point_groups)
  {
    Tensor<1, 3> mean;
    for (const auto& x : group.points)
      mean += problem.probe_vector(problem.make_probe(x, "FEM/Measurements/point groups")) /
              double(group.points.size());
    summary["mean_displacements"][group.name] = {mean[0], mean[1], mean[2]};
  }
}

/// The mean stress in the slabs of FEM/Measurements/stress layers.
nlohmann::json stress_layer_figures(const ElasticProblem& problem, const Parameters& p)
{
  const auto layers = problem.layer_stresses(p.stress_layer_axis, p.stress_layer_edges);
  nlohmann::json sigma = nlohmann::json::array();
  for (const auto& s : layers.sigma)
    sigma.push_back(
        {{s[0][0], s[0][1], s[0][2]}, {s[1][0], s[1][1], s[1][2]}, {s[2][0], s[2][1], s[2][2]}});
  return {{"axis", std::string(1, char('x' + p.stress_layer_axis))},
          {"edges", p.stress_layer_edges},
          {"volume", layers.volume},
          {"sigma", sigma}};
}

CaseResult run_static(const Parameters& p, MPI_Comm comm, CaseObserver& observer)
{
  ElasticProblem problem(p, comm);
  const unsigned int iterations = solve_static(problem, comm);
  CaseResult result;
  nlohmann::json& summary = result.figures;
  summary["n_dofs"] = problem.n_dofs();
  summary["n_cells"] = problem.n_cells();
  summary["solver_iterations"] = iterations;
  summary["strain_energy"] = problem.strain_energy();
  measure_static(problem, p, summary);
  if (p.stress_layer_axis >= 0)
    summary["stress_layers"] = stress_layer_figures(problem, p);
  const auto times = problem.timer().get_summary_data(TimerOutput::total_wall_time);
  for (const auto& [section, seconds] : times)
  {
    std::string key = section;
    std::replace(key.begin(), key.end(), ' ', '_');
    summary["timing"][key + "_seconds"] = Utilities::MPI::max(seconds, comm);
  }
  observer.on_solved(problem);
  result.timing_table = timing_table(problem.timer(), comm);
  return result;
}

/// What the dynamics loop carries from step to step beside the continuum (a checkpoint's
/// /fem_run/): the steps done, the running summaries of the energies and the zero crossings
/// that the summary reads at the end (a few numbers however long the run), the probe component
/// followed, the next checkpoint time, the caller's history length at the checkpoint.
struct DynamicsLoopState
{
  long steps = 0; ///< steps done
  dem::RunningSeries shadow, total;
  long crossings = 0; ///< zero crossings of the followed component
  double first_crossing = 0, last_crossing = 0;
  double previous_value = 0, previous_time = 0;
  int component = 0;
  double next_checkpoint_time = 0;
  long history_bytes = 0; ///< the caller's history length at the checkpoint (rank 0)

  void visit(dem::StateArchive& a)
  {
    dem::StateGroup group(a, "fem_run");
    a.io("steps", steps);
    shadow.visit(a, "shadow_energy");
    total.visit(a, "total_energy");
    a.io("zero_crossings", crossings);
    a.io("first_crossing", first_crossing);
    a.io("last_crossing", last_crossing);
    a.io("previous_value", previous_value);
    a.io("previous_time", previous_time);
    a.io("component", component);
    a.io("next_checkpoint_time", next_checkpoint_time);
    a.io("history_bytes", history_bytes);
  }
};

/// Explicit dynamics: n steps of size factor * dt_stable; the probes' displacements and the
/// energies of every step go to the observer; the natural frequency from the zero crossings of
/// the first probe's dominant displacement component (free vibration about u = 0). With
/// checkpoints the loop's state and the continuum's are saved between steps and restored
/// before the first.
class DynamicsRun
{
public:
  DynamicsRun(const Parameters& parameters, MPI_Comm communicator, CaseObserver& case_observer,
              const DynamicsCheckpoints* dynamics_checkpoints)
      : p(parameters), comm(communicator), observer(case_observer),
        checkpoints(dynamics_checkpoints), problem(parameters, communicator),
        root(Utilities::MPI::this_mpi_process(communicator) == 0)
  {
  }

  CaseResult run()
  {
    start();
    for (unsigned int n = unsigned(loop.steps); n < p.n_steps; ++n)
    {
      advance(n);
      loop.steps = long(n) + 1;
      if (checkpoint_due() && n + 1 < p.n_steps) // none after the last step: the run completes
        checkpoint();
      if (checkpoints && checkpoints->after_step)
        checkpoints->after_step(loop.steps);
    }
    observer.on_dynamics_end(problem);
    CaseResult result;
    result.figures = figures();
    result.timing_table = timing_table(problem.timer(), comm);
    return result;
  }

private:
  /// Sets the continuum up, picks the followed component, restores a resumed run's state and
  /// tells the observer where the run starts.
  void start()
  {
    ConditionalOStream pcout(std::cout, root);
    problem.setup();
    dt = p.time_step_factor * problem.stable_time_step();
    pcout << "FEM dynamics: " << problem.n_cells() << " cells, " << problem.n_dofs()
          << " dofs, stable step " << problem.stable_time_step() << " s, step " << dt << " s"
          << std::endl;
    for (const auto& x : p.probe_points)
      probes.push_back(problem.make_probe(x, "FEM/Dynamics/probe points"));
    if (!probes.empty())
    {
      const Tensor<1, 3> u0 = problem.probe_vector(probes[0]);
      for (unsigned int d = 1; d < 3; ++d)
        if (std::abs(u0[d]) > std::abs(u0[loop.component]))
          loop.component = int(d);
    }
    loop.next_checkpoint_time = checkpoints ? checkpoints->interval : 0.0;
    const bool resumed = checkpoints && checkpoints->resume;
    if (resumed)
    {
      if (root)
        checkpoints->read([this](dem::StateArchive& a) { visit(a); });
      problem.scatter_state(); // collective: each rank's part of the continuum
      broadcast_state(comm, [&](dem::StateArchive& a) { loop.visit(a); });
    }
    observer.on_dynamics_start(problem, {probes.size(), loop.steps, resumed, loop.history_bytes});
    last_checkpoint = std::chrono::steady_clock::now();
  }

  /// Step n: the probes at t_n, the step, the energies' series and the zero crossings.
  void advance(const unsigned int n)
  {
    const double t_n = problem.time();
    u.clear();
    for (const auto& probe : probes)
      u.push_back(problem.probe_vector(probe));
    problem.step(dt); // energies below belong to step n (time t_n)
    const auto& e = problem.energies();
    loop.shadow.add(e.shadow_total());
    loop.total.add(e.total());
    if (!u.empty())
    {
      const double value = u[0][loop.component];
      if (n > 0 && loop.previous_value * value < 0)
      {
        loop.last_crossing = loop.previous_time + (t_n - loop.previous_time) * loop.previous_value /
                                                      (loop.previous_value - value);
        if (loop.crossings++ == 0)
          loop.first_crossing = loop.last_crossing;
      }
      loop.previous_value = value;
      loop.previous_time = t_n;
    }
    observer.on_step(problem, {n, t_n, u, e});
  }

  /// A checkpoint is due after this step: by simulated time, or by rank 0's wall clock.
  bool checkpoint_due()
  {
    const double interval = checkpoints ? checkpoints->interval : 0.0;
    const double wall_interval = checkpoints ? checkpoints->wall_interval : 0.0;
    bool due = false;
    if (interval > 0 && problem.time() + 0.5 * dt >= loop.next_checkpoint_time)
    {
      due = true;
      while (loop.next_checkpoint_time <= problem.time() + 0.5 * dt)
        loop.next_checkpoint_time += interval;
    }
    if (wall_interval > 0)
    {
      // why: the ranks' clocks differ and a checkpoint is collective: rank 0's clock decides
      const bool late =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint)
              .count() >= wall_interval;
      due = Utilities::MPI::broadcast(comm, late, 0) || due;
    }
    return due;
  }

  void checkpoint()
  {
    problem.gather_state(); // collective
    if (root)
    {
      loop.history_bytes = observer.history_length();
      checkpoints->write(loop.steps, problem.time(), [this](dem::StateArchive& a) { visit(a); });
    }
    last_checkpoint = std::chrono::steady_clock::now();
  }

  /// A checkpoint's content: the continuum's state and the loop's.
  void visit(dem::StateArchive& a)
  {
    problem.visit_state(a);
    loop.visit(a);
  }

  nlohmann::json figures() const
  {
    const dem::RunningSeries& shadow = loop.shadow;
    nlohmann::json summary;
    summary["n_dofs"] = problem.n_dofs();
    summary["n_cells"] = problem.n_cells();
    summary["steps"] = p.n_steps;
    summary["time_step"] = dt;
    summary["stable_time_step"] = problem.stable_time_step();
    summary["end_time"] = problem.time();
    if (shadow.count > 0 && shadow.first != 0)
    {
      summary["initial_energy"] = shadow.first;
      summary["shadow_energy_relative_oscillation"] = shadow.relative_range();
      // drift: the least-squares line's change over the run, relative to H_0
      summary["shadow_energy_relative_drift"] = shadow.fitted_change() / std::abs(shadow.first);
      summary["total_energy_relative_oscillation"] = loop.total.relative_range();
    }
    if (loop.crossings >= 2)
    {
      // Successive zero crossings are half a period apart: first to last crossing.
      const double half_period =
          (loop.last_crossing - loop.first_crossing) / double(loop.crossings - 1);
      summary["natural_frequency"] = 1.0 / (2.0 * half_period);
      summary["zero_crossings"] = loop.crossings;
    }
    return summary;
  }

  const Parameters& p;
  MPI_Comm comm;
  CaseObserver& observer;
  const DynamicsCheckpoints* checkpoints;
  ExplicitDynamics problem;
  const bool root;
  double dt = 0;
  std::vector<PointProbe> probes;
  DynamicsLoopState loop;
  std::vector<Tensor<1, 3>> u; ///< the probes' displacements, refilled each step
  std::chrono::steady_clock::time_point last_checkpoint;
};
} // namespace

void remove_later_fe_snapshots(const std::filesystem::path& dir, const std::string& base,
                               const std::vector<std::pair<double, std::string>>& records)
{
  std::set<std::string> listed; // fem_0003.pvtu: its pieces are fem_0003.*.vtu
  for (const auto& r : records)
    listed.insert(r.second.substr(0, r.second.find('.')));
  for (const auto& entry : std::filesystem::directory_iterator(dir))
  {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    if ((ext == ".vtu" || ext == ".pvtu") && name.rfind(base + "_", 0) == 0 &&
        !listed.count(name.substr(0, name.find('.'))))
      std::filesystem::remove(entry.path());
  }
}

CaseResult run_case(const Parameters& p, MPI_Comm comm, CaseObserver& observer,
                    const DynamicsCheckpoints* checkpoints)
{
  if (p.incompatible_modes && p.problem == ProblemKind::static_elasticity)
    throw std::runtime_error("FEM/incompatible modes: explicit dynamics and coupled runs only "
                             "(a static run's stresses and strain energy are evaluated on the "
                             "nodal field)");
  CaseResult result = p.problem == ProblemKind::static_elasticity
                          ? run_static(p, comm, observer)
                          : DynamicsRun(p, comm, observer, checkpoints).run();
  nlohmann::json& summary = result.figures;
  summary["mode"] = "fem";
  summary["problem"] = p.problem == ProblemKind::static_elasticity ? "static" : "dynamics";
  summary["degree"] = p.degree;
  summary["n_ranks"] = Utilities::MPI::n_mpi_processes(comm);
  if (p.material == MaterialModel::isotropic)
  {
    summary["youngs_modulus_input"] = p.youngs_modulus;
    summary["poisson_ratio_input"] = p.poisson_ratio;
  }
  return result;
}

void write_fields(ElasticProblem& problem, const std::filesystem::path& dir,
                  const unsigned int cycle, const double time)
{
  problem.output_results(dir, cycle, time);
}
} // namespace dembridge::fem
