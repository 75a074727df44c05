#include "app/runs/dem_static_run.h"
#include "app/output/contact_output.h"
#include "app/output/dem_history.h"
#include "app/output/particle_vtu.h"
#include "dem/core/output_file.h"
#include "dem/measurements/particle_stress.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "fem/bond_network_solver.h"
#endif
#include <cstdio>
#include <iomanip>

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

// auto: GAMG from 150 k unknowns, where it starts to beat Jacobi CG (bench/RESULTS_STATIC.md)
dem::StaticSettings static_solver_settings(dealii::ParameterHandler& prm)
{
  dem::StaticSettings base;
  const std::string linear = prm.get({"Simulation"}, "static linear solver");
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

StaticRun run_static_load_steps(dem::Model& model, const dem::CaseConfig& config,
                                const OutputSettings& out, const std::filesystem::path& dir,
                                const dem::StaticSettings& base)
{
  assign_group_masks(model);
  StaticRun run;
  run.load_steps = out.load_steps;
  const int n = out.load_steps;
  const double end = config.run.end_time;
  const ContactOutput contacts(model);
  const std::filesystem::path part = dir / "history.csv.part";
  dem::OutputFile history(part); // failures name the file and the reason
  history << history_header(model, contacts) << std::setprecision(10);
  ParticleVtuSeries vtu(dir, group_names(model));
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
    std::printf("static load step %d/%d (t = %.4g s): %ld unknowns, %s, %ld iterations, %.3g s\n",
                k, n, t, st.n_free_dofs, st.method.c_str(), st.iterations,
                st.assembly_seconds + st.solve_seconds);
    std::fflush(stdout);
    HistoryRecord r;
    r.step = k;
    r.time = t;
    r.energy.strain = dem::particle_stresses(model.particles, model.bonds).strain_energy;
    r.energy.external = r.energy.strain; // Clapeyron: linear, loaded slowly from rest
    r.unbalanced_force_ratio = unbalanced_force_ratio(model.particles, model.bonds);
    history_row(history, r, model.particles, model.groups, contacts);
    const bool snapshot =
        k == 1 || k == n || (out.snapshot_interval > 0 && k % out.snapshot_interval == 0);
    if (out.write_vtu && snapshot)
      vtu.write(model.particles, model.bonds, t, k);
  }
  history.close();
  std::filesystem::rename(part, dir / "history.csv");
  if (out.write_vtu)
    vtu.finish();
  return run;
}
} // namespace dembridge::app
