#include "app/runs/dem_run.h"
#include "app/checkpoint/checkpoint.h"
#include "app/input/dem_parameters.h"
#include "app/output/contact_output.h"
#include "app/output/crack_output.h"
#include "app/output/dem_figures.h"
#include "app/output/result_warnings.h"
#include "app/runs/dem_observer.h"
#include "app/runs/dem_run_ranks.h"
#include "app/runs/dem_static_run.h"
#include "dem/measurements/particle_stress.h"
#include "dem/solvers/run_explicit.h"
#include "dem/solvers/static_solver.h"
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace dembridge::app
{
namespace
{
/// What an explicit run leaves for the figures measured on its final state.
struct ExplicitCaseRun
{
  dem::RunResult result;
  LoadHistory history;
  std::vector<dem::CrackEvent> cracks;
};

/// An explicit run (on every MPI rank of the job): history.csv, snapshots, checkpoints, and its
/// cracks, kinetic energy, energy balance and contact figures.
ExplicitCaseRun run_explicit_case(dem::Model& model, const dem::CaseConfig& config,
                                  const OutputSettings& out, const std::filesystem::path& dir,
                                  const CheckpointSettings& checkpoint, nlohmann::json& j)
{
  const bool failure_law = config.damage.law.mode != dem::FailureMode::none;
  CaseObserver observer(dir, out, model, checkpoint, failure_law);
  if (!config.measure.modulus_fixed_group.empty())
    observer.track_axial(
        model.group_index(config.measure.modulus_fixed_group, "Measurements/modulus groups"),
        model.group_index(config.measure.modulus_loaded_group, "Measurements/modulus groups"),
        config.measure.modulus_axis);
  if (config.measure.flexural_groups.size() == 4)
  {
    const auto& f = config.measure.flexural_groups;
    const auto where = "Measurements/flexural groups";
    observer.track_flexural(model.group_index(f[0], where), model.group_index(f[1], where),
                            model.group_index(f[2], where), model.group_index(f[3], where));
  }
  dem::RunSchedule schedule;
  schedule.record_interval = out.history_interval;
  schedule.snapshot_interval = out.snapshot_interval;
  schedule.checkpoint_interval = checkpoint.file.empty() ? 0.0 : checkpoint.interval;
  schedule.checkpoint_wall_interval = checkpoint.file.empty() ? 0.0 : checkpoint.wall_interval;
  if (const char* kill = std::getenv("DEMBRIDGE_TEST_KILL_AFTER_STEP")) // tests (checkpoint.h)
    schedule.kill_after_step = std::atol(kill);
  ExplicitCaseRun run;
  run.result = run_explicit_on_ranks(model, config, observer, schedule, checkpoint, dir,
                                     observer.particle_snapshots(), j);
  const dem::RunResult& r = run.result;
  observer.finish();
  run.history = observer.load_history();
  run.cracks = observer.cracks().cracks();
  if (failure_law)
    add_crack_summary(j, run.cracks, model.particles, model.bonds, config.measure.stress_layers,
                      config.measure.stress_layer_axis, config.measure.modulus_axis);
  else
    add_bond_class_summary(j, model.particles, model.bonds);
  const auto [share_max, share_final] = observer.kinetic_share();
  j["kinetic_energy_share_max"] = share_max;
  j["kinetic_energy_share_final"] = share_final;
  j["solver"] = {{"type", "explicit"}};
  // co-rotational bonds, rotations integrated exactly (bond_kernel.h, orientation_update.h)
  j["geometry"] = "nonlinear (large displacements and rotations)";
  if (checkpoint.resume)
    j["resumed_from"] = {{"file", checkpoint.file.string()},
                         {"step", checkpoint.resumed_step},
                         {"time", checkpoint.resumed_time}};
  j["time_step"] = model.time_step;
  j["steps"] = r.steps;
  j["simulated_time"] = r.time;
  j["bond_updates_per_second"] =
      r.wall_seconds > 0 ? double(r.steps_made) * double(model.bonds.size()) / r.wall_seconds : 0.0;
  add_energy_figures(j, r);
  ContactOutput(model).summary(j, r.time);
  return run;
}

/// A static run has no time steps: checkpoints and --resume are refused.
void refuse_static_checkpoints(const dem::CaseConfig& config, const CheckpointSettings& checkpoint)
{
  if (config.run.static_solver && (checkpoint.enabled() || checkpoint.resume))
    throw dem::InputError(
        std::string(checkpoint.resume ? "--resume" : "Output/checkpoint interval") +
        ": the static solver has no time steps to checkpoint (explicit runs "
        "only)");
}
} // namespace

nlohmann::json run_dem_case(dealii::ParameterHandler& prm, const std::filesystem::path& dir,
                            CheckpointSettings checkpoint)
{
  dem::CaseConfig config = parse_dem_case(prm);
  if (!config.run.static_solver)
    check_explicit_end_time(config.run.end_time, config.particles.save_file);
  // per-bond force records feed the static run's figures only (ParaView bond files evaluate
  // each bond on demand)
  config.run.bond_force_records = config.run.static_solver;
  const OutputSettings out = parse_output_settings(prm);
  checkpoint.interval = out.checkpoint_interval;
  checkpoint.wall_interval = out.checkpoint_wall_interval;
  refuse_static_checkpoints(config, checkpoint);
  dem::Model model = dem::build_model(config);
  if (run_dem_case_on_other_rank(config, model, checkpoint, dir, out.write_vtu)) // mpirun -np N
    return {};
  std::printf("DEM: %zu particles, %zu bonds (%s), time step %.4g s (critical %.4g s; thesis "
              "eq. 48: %.4g s)\n",
              model.particles.size(), model.bonds.size(), prm.get({"Bonds"}, "model").c_str(),
              model.time_step, model.critical.critical(), model.critical.thesis_eq48);
  std::fflush(stdout);

  nlohmann::json j;
  j["warnings"] = nlohmann::json::array();
  check_bond_coverage(model.particles, model.bonds.size(), config, j);
  if (!config.run.static_solver && config.run.end_time == 0) // check_explicit_end_time let it by
    add_warning(j, "simulated_time: end time 0: the packing was written (Particles/save file) "
                   "and nothing was simulated; the figures are those of the unloaded specimen");
  // a static run records no load history and breaks no bond
  ExplicitCaseRun run;
  if (config.run.static_solver)
    run.result = add_static_run_figures(
        j, model, config,
        run_static_load_steps(model, config, out, dir, static_solver_settings(prm)));
  else
    run = run_explicit_case(model, config, out, dir, checkpoint, j);
  const dem::ParticleStresses stresses = dem::particle_stresses(model.particles, model.bonds);
  write_particle_stresses(dir / "particle_stress.csv", model.particles, stresses);
  add_final_state_figures(j, model, config, prm.get({"Bonds"}, "model"), run.result, stresses,
                          run.history, !run.cracks.empty());
  return j;
}
} // namespace dembridge::app
