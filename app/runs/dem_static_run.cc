#include "app/runs/dem_static_run.h"
#include "app/output/contact_output.h"
#include "app/output/crack_output.h"
#include "app/output/dem_history.h"
#include "app/output/particle_vtu.h"
#include "app/output/result_warnings.h"
#include "dem/core/output_file.h"
#include "dem/measurements/particle_stress.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "fem/bond_network_solver.h"
#endif
#include <cmath>
#include <cstdio>
#include <deal.II/base/mpi.h>
#include <iomanip>
#include <optional>

namespace dembridge::app
{
void assign_group_masks(dem::Model& model)
{
  for (std::size_t g = 0; g < model.groups.size() && g < 32; ++g)
    for (int i : model.groups[g].members)
      model.particles.group_mask[std::size_t(i)] |= 1u << g;
}

std::vector<std::string> group_names(const dem::Model& model)
{
  std::vector<std::string> names;
  for (std::size_t g = 0; g < model.groups.size() && g < 32; ++g)
    names.push_back(model.groups[g].name);
  return names;
}

namespace
{
unsigned n_ranks()
{
  return dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
}

/// What the ranks other than 0 need of the case to take part in a static run's solves: rank 0's
/// Simulation/load steps and static linear solver (0 auto, 1 cg, 2 gamg).
struct StaticRankPlan
{
  int load_steps = 1;
  int linear_solver = 0;
};

/// Rank 0's plan on every rank (collective on MPI_COMM_WORLD).
StaticRankPlan share_plan(StaticRankPlan plan)
{
  MPI_Bcast(&plan, 2, MPI_INT, 0, MPI_COMM_WORLD);
  return plan;
}

/// The solver settings of a static run on several ranks: every system, whatever its size, by
/// PETSc's CG on the ranks' shared matrix (GAMG, or for cg the Jacobi scaling alone); no
/// factorisation, which would be serial.
dem::StaticSettings settings_on_ranks([[maybe_unused]] int linear_solver)
{
#ifdef DEMBRIDGE_HAVE_FEM
  dem::StaticSettings base;
  base.method = dem::StaticSettings::Method::cg_jacobi;
  base.cg_tolerance = static_solver_tolerance;
  fem::GamgSettings gamg;
  gamg.communicator = MPI_COMM_WORLD;
  gamg.multigrid = linear_solver != 1;
  base.iterative_solver = fem::gamg_iterative_solver(gamg);
  base.iterative_solver_min_unknowns = 0;
  return base;
#else
  throw dem::InputError("Simulation/solver: the static solver on several MPI ranks needs PETSc, "
                        "and this dembridge was built without the fem layer (run it on one rank)");
#endif
}
} // namespace

// auto: GAMG from 150 k unknowns, where it starts to beat Jacobi CG (bench/RESULTS_STATIC.md)
dem::StaticSettings static_solver_settings(dealii::ParameterHandler& prm)
{
  dem::StaticSettings base;
  base.cg_tolerance = static_solver_tolerance;
  const std::string linear = prm.get({"Simulation"}, "static linear solver");
  if (n_ranks() > 1)
  {
    StaticRankPlan plan;
    plan.load_steps = int(prm.get_integer({"Simulation"}, "load steps"));
    plan.linear_solver = linear == "cg" ? 1 : linear == "gamg" ? 2 : 0;
    return settings_on_ranks(share_plan(plan).linear_solver);
  }
#ifdef DEMBRIDGE_HAVE_FEM
  if (linear != "cg")
    base.iterative_solver = fem::gamg_iterative_solver();
  base.iterative_solver_min_unknowns = linear == "auto" ? 150000 : 0;
#else
  if (linear == "gamg")
    throw dem::InputError("Simulation/static linear solver: gamg needs PETSc, and this "
                          "dembridge was built without the fem layer (use auto or cg)");
#endif
  return base;
}

void solve_static_on_other_rank(dem::Model& model, const dem::CaseConfig& config)
{
  const StaticRankPlan plan = share_plan({});
  solve_static_load_steps(model, config, plan.load_steps, settings_on_ranks(plan.linear_solver));
}

namespace
{
/// The explicit solver's unbalanced-force ratio (explicit_solver.h) of a static state: the mean
/// net force on free translational DOFs over the mean force of the intact bonds.
double unbalanced_force_ratio(const dem::ParticleStore& p, const dem::BondStore& b)
{
  double net = 0, bond = 0;
  long n_free = 0, n_intact = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p.dof_mask[i] & 7u) != 7u)
    {
      dem::Vec3 free = p.force[i];
      for (int k = 0; k < 3; ++k)
        if (p.dof_mask[i] & (1u << k))
          free[k] = 0;
      net += free.norm(), ++n_free;
    }
  for (std::size_t k = 0; k < b.size(); ++k)
    if (b.state[k] == dem::BondState::intact)
      bond += b.force[k].norm(), ++n_intact;
  if (!(bond > 0) || n_free == 0)
    return 0.0;
  return (net / double(n_free)) / (bond / double(n_intact));
}
} // namespace

HistoryRecord static_step_record(const dem::Model& model, int k, double t)
{
  HistoryRecord r;
  r.step = k;
  r.time = t;
  r.energy.strain = dem::particle_stresses(model.particles, model.bonds).strain_energy;
  r.energy.external = r.energy.strain; // Clapeyron: linear, loaded slowly from rest
  r.unbalanced_force_ratio = unbalanced_force_ratio(model.particles, model.bonds);
  return r;
}

StaticRun solve_static_load_steps(dem::Model& model, const dem::CaseConfig& config, int load_steps,
                                  const dem::StaticSettings& base, const StaticStepDone& step_done)
{
  StaticRun run;
  run.load_steps = load_steps;
  const int n = load_steps;
  const double end = config.run.end_time;
  for (int k = 1; k <= n; ++k)
  {
    dem::StaticSettings settings = base;
    if (k < n) // the last step is the final state (static_solver.h)
      settings.time = end * double(k) / double(n);
    const double t = k < n ? settings.time : end;
    const dem::StaticResult st = dem::solve_static(model, settings);
    run.seconds += st.assembly_seconds + st.solve_seconds;
    run.last = st;
    dem::record_bond_forces(model.particles, model.bonds);
    if (step_done)
      step_done(k, t, st);
  }
  return run;
}

StaticRun run_static_load_steps(dem::Model& model, const dem::CaseConfig& config,
                                const OutputSettings& out, const std::filesystem::path& dir,
                                const dem::StaticSettings& base)
{
  assign_group_masks(model);
  const int n = out.load_steps;
  const ContactOutput contacts(model);
  const std::filesystem::path part = dir / "history.csv.part";
  dem::OutputFile history(part); // failures name the file and the reason
  history << history_header(model, contacts) << std::setprecision(10);
  ParticleVtuSeries vtu(dir, group_names(model));
  const auto write_step = [&](int k, double t, const dem::StaticResult& st)
  {
    std::printf("static load step %d/%d (t = %.4g s): %ld unknowns, %s, %ld iterations, %.3g s\n",
                k, n, t, st.n_free_dofs, st.method.c_str(), st.iterations,
                st.assembly_seconds + st.solve_seconds);
    std::fflush(stdout);
    history_row(history, static_step_record(model, k, t), model.particles, model.groups, contacts);
    const bool snapshot =
        k == 1 || k == n || (out.snapshot_interval > 0 && k % out.snapshot_interval == 0);
    if (out.write_vtu && snapshot)
      vtu.write(model.particles, model.bonds, t, k);
  };
  const StaticRun run = solve_static_load_steps(model, config, n, base, write_step);
  history.close();
  std::filesystem::rename(part, dir / "history.csv");
  if (out.write_vtu)
    vtu.finish();
  return run;
}

dem::RunResult add_static_run_figures(nlohmann::json& j, const dem::Model& model,
                                      const dem::CaseConfig& config, const StaticRun& run)
{
  const dem::StaticResult& st = run.last;
  dem::RunResult r;
  r.stop_reason = "static";
  r.wall_seconds = run.seconds;
  j["load_steps"] = run.load_steps;
  if (!config.measure.deflection_group.empty())
  {
    const auto& g = model.groups[model.group_index(config.measure.deflection_group,
                                                   "Measurements/deflection group")];
    r.deflection_vector = dem::mean_displacement(model.particles, g);
    r.deflection = r.deflection_vector.dot(config.measure.deflection_direction.normalized());
  }
  add_static_geometry(j, model);
  add_bond_class_summary(j, model.particles, model.bonds);
  j["solver"] = {{"type", "static"},
                 {"method", st.method},
                 {"iterations", st.iterations},
                 {"residual", st.residual},
                 {"n_free_dofs", st.n_free_dofs},
                 {"held_unbonded_particles", st.held_unbonded},
                 {"assembly_seconds", st.assembly_seconds},
                 {"solve_seconds", st.solve_seconds},
                 {"preconditioner_setup_seconds", st.setup_seconds}};
  return r;
}

namespace
{
double mean_coordination(const dem::ParticleStore& p)
{
  double mean = 0;
  for (int c : p.coordination)
    mean += c;
  return mean / double(p.size());
}

/// The natural frequency of Measurements/frequency group; null with a warning when the group did
/// not swing often enough to measure it.
void add_natural_frequency(nlohmann::json& j, const dem::RunResult& r,
                           const dem::MeasureConfig& measure)
{
  if (r.natural_frequency)
    j["natural_frequency"] = *r.natural_frequency;
  else if (!measure.frequency_group.empty())
  {
    j["natural_frequency"] = nullptr;
    add_warning(j, "natural_frequency: undefined: group '" + measure.frequency_group +
                       "' (Measurements/frequency group) did not swing through its mean at least "
                       "three times in the run (a longer Simulation/end time, or less damping); "
                       "written as null");
  }
}
} // namespace

void add_final_state_figures(nlohmann::json& j, const dem::Model& model,
                             const dem::CaseConfig& config, const std::string& bond_model,
                             const dem::RunResult& r, const dem::ParticleStresses& stresses,
                             const LoadHistory& history, bool broke)
{
  // particle stresses (thesis eq. 62), their histogram (Fig. 36) and slab averages (eq. 54)
  const auto extent = dem::reference_extent(model.particles);
  const std::optional<dem::StressLayers> layers =
      add_particle_stress_figures(j, model, config.measure, stresses, extent);
  j["porosity"] = model.porosity;
  j["packing_volume"] = model.packing_volume;
  j["mode"] = "dem";
  j["bond_model"] = bond_model;
  j["n_particles"] = model.particles.size();
  j["n_bonds"] = model.bonds.size();
  j["mean_coordination"] = mean_coordination(model.particles);
  j["critical_time_step"] = model.critical.critical();
  if (std::isfinite(model.critical.thesis_eq48)) // eq. 48 bounds bonds: none without them
    j["critical_time_step_eq48"] = model.critical.thesis_eq48;
  j["stop_reason"] = r.stop_reason;
  j["solver_seconds"] = r.wall_seconds;
  if (r.deflection)
  {
    j[config.measure.deflection_name] = *r.deflection;
    j[config.measure.deflection_name + "_vector"] = to_json(r.deflection_vector);
  }
  if (!config.measure.modulus_fixed_group.empty())
    add_axial_figures(j, model, config.measure, stresses, extent, layers, history, broke);
  if (!config.measure.flexural_groups.empty())
    add_flexural_figures(j, model, config.measure, history, broke);
  add_natural_frequency(j, r, config.measure);
  add_group_figures(j, model);
}
} // namespace dembridge::app
