#include "dem_run.h"
#include "checkpoint.h"
#include "contact_output.h"
#include "crack_output.h"
#include "dem/core/history_file.h"
#include "dem/core/output_file.h"
#include "dem/measurements/failure_measurements.h"
#include "dem/measurements/measurements.h"
#include "dem/measurements/particle_stress.h"
#include "dem/solvers/run_explicit.h"
#include "dem/solvers/static_solver.h"
#include "dem_history.h"
#include "dem_parameters.h"
#include "dem_run_ranks.h"
#include "dem_static_run.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "fem/bond_network_solver.h"
#endif
#include "particle_vtu.h"
#include "provenance.h"
#include "result_warnings.h"
#include "version.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deal.II/base/mpi.h>
#include <iomanip>
#include <iostream>
#include <optional>

namespace dembridge::app
{
namespace
{
/// Rotations (rad) above which a linear (static) solution is flagged: it differs from the
/// large-rotation one by about half the rotation squared (a cantilever's tip deflection against
/// the explicit solver's: 1.2e-5 at 5.1e-3 rad, 1.4e-4 at 0.017 rad, 1.2e-3 at 0.051 rad), 5e-5
/// here.
constexpr double max_linear_rotation = 1e-2;

nlohmann::json to_json(const dem::Vec3& v)
{
  return {v.x(), v.y(), v.z()};
}

nlohmann::json to_json(const dem::Tensor3& t)
{
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    rows.push_back({t(r, 0), t(r, 1), t(r, 2)});
  return rows;
}

/// particle_stress.csv: reference position, radius and stress tensor (Pa) of every particle;
/// written under a temporary name and renamed, so a partial file never looks complete.
void write_particle_stresses(const std::filesystem::path& file, const dem::ParticleStore& p,
                             const dem::ParticleStresses& s)
{
  const std::filesystem::path part = file.string() + ".part";
  {
    dem::OutputFile out(part); // failures name the file and the reason
    out << "id,x,y,z,radius,s_xx,s_yy,s_zz,s_yz,s_xz,s_xy\n" << std::setprecision(10);
    // rows in the user's particle numbering (the stores are in spatial order, renumbering.h)
    std::vector<std::size_t> by_id(p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      by_id[std::size_t(p.id[i])] = i;
    for (const std::size_t i : by_id)
    {
      const auto& x = p.reference_position[i];
      const auto& t = s.sigma[i];
      // symmetric part (the antisymmetric part is the neglected couples' share)
      out << p.id[i] << ',' << x.x() << ',' << x.y() << ',' << x.z() << ',' << p.radius[i] << ','
          << t(0, 0) << ',' << t(1, 1) << ',' << t(2, 2) << ',' << 0.5 * (t(1, 2) + t(2, 1)) << ','
          << 0.5 * (t(0, 2) + t(2, 0)) << ',' << 0.5 * (t(0, 1) + t(1, 0)) << '\n';
    }
    out.close();
  }
  std::filesystem::rename(part, file);
}

/// history.csv (one row per record), ParaView snapshots and console progress.
class CaseObserver : public dem::RunObserver
{
public:
  CaseObserver(const std::filesystem::path& dir, const OutputSettings& out, const dem::Model& model,
               const CheckpointSettings& checkpoint, bool failure_law)
      : model_(model), vtu_(dir, group_names(model)), write_vtu_(out.write_vtu), dir_(dir),
        history_path_(dir / "history.csv"), cracks_(dir, out.write_vtu, failure_law),
        checkpoint_(checkpoint)
  {
    // Written under a temporary name and renamed when the run completes, so an interrupted
    // run never leaves a history that looks complete.
    // A resume keeps the interrupted run's file; visit_state cuts it back to the checkpoint.
    history_file_.open(dir / "history.csv.part", checkpoint.resume);
    if (!checkpoint.resume)
      history_ << history_header(model, contacts_);
    history_ << std::setprecision(10);
  }

  /// Records the loaded end's axial reaction against the end groups' relative displacement
  /// (the force-displacement curve of thesis eq. 64).
  void track_axial(int fixed, int loaded, int axis)
  {
    fixed_ = fixed, loaded_ = loaded, axis_ = axis;
  }
  const std::vector<double>& axial_displacements() const { return du_; }
  /// Records the load a three-point bending specimen carries (the supports' vertical
  /// reactions) against the midspan deflection: the mean downward displacement of the loaded
  /// and the bottom groups (thesis eq. 69's delta, as flexural_response's).
  void track_flexural(int pin, int roller, int loaded, int bottom)
  {
    pin_ = pin, roller_ = roller, top_ = loaded, bottom_ = bottom;
  }
  const std::vector<double>& flexural_loads() const { return flex_load_; }
  const std::vector<double>& flexural_deflections() const { return flex_u_; }
  /// Records of the flexural history before the first bond broke: its elastic part.
  std::size_t flexural_records_intact() const
  {
    return std::size_t(std::find_if(flex_broken_.begin(), flex_broken_.end(),
                                    [](std::int64_t n) { return n > 0; }) -
                       flex_broken_.begin());
  }
  const CrackOutput& cracks() const { return cracks_; }
  /// Axial load history: the loaded end's reaction, or (force control) minus the fixed end's.
  const std::vector<double>& axial_forces(bool from_fixed_end) const
  {
    return from_fixed_end ? fixed_force_ : force_;
  }
  /// Largest kinetic share KE / (KE + strain energy) over the second half of the run, and the
  /// last one: how quasi-static the loading was.
  std::pair<double, double> kinetic_share() const
  {
    double largest = 0;
    const double t_end = kinetic_share_.empty() ? 0 : kinetic_share_.back().first;
    for (const auto& [t, share] : kinetic_share_)
      if (t >= 0.5 * t_end)
        largest = std::max(largest, share);
    return {largest, kinetic_share_.empty() ? 0.0 : kinetic_share_.back().second};
  }

  void on_record(const dem::ExplicitSolver& s) override
  {
    if (loaded_ >= 0)
    {
      du_.push_back(s.group_mean_displacement(loaded_)[axis_] -
                    s.group_mean_displacement(fixed_)[axis_]);
      force_.push_back(s.group_force(loaded_)[axis_]);
      fixed_force_.push_back(-s.group_force(fixed_)[axis_]);
    }
    if (top_ >= 0)
    {
      flex_load_.push_back(s.group_force(pin_).z() + s.group_force(roller_).z());
      flex_u_.push_back(
          -0.5 * (s.group_mean_displacement(top_).z() + s.group_mean_displacement(bottom_).z()));
      flex_broken_.push_back(s.n_broken_bonds());
    }
    cracks_.update(s);
    const auto& e = s.energy();
    if (e.kinetic + e.strain > 0)
      kinetic_share_.emplace_back(s.time(), e.kinetic / (e.kinetic + e.strain));
    history_row(
        history_,
        {s.steps(), s.time(), e, s.max_speed(), s.unbalanced_force_ratio(), s.n_broken_bonds()},
        model_.particles, s.groups(), contacts_);
  }

  void on_start(dem::ExplicitSolver& s, dem::RunProgress& progress) override
  {
    if ((checkpoint_.enabled() || checkpoint_.resume) && !s.checkpointable())
      throw dem::InputError("Output/checkpoint interval: this run has forces (a coupling?) "
                            "that cannot be checkpointed yet");
    if (!checkpoint_.resume)
      return;
    read_checkpoint(checkpoint_.file, [&](dem::StateArchive& a) { visit_state(a, s, progress); });
    std::printf("resumed from %s: step %ld, t = %.6g s\n", checkpoint_.file.string().c_str(),
                s.steps(), s.time());
    std::fflush(stdout);
  }

  void on_checkpoint(dem::ExplicitSolver& s, dem::RunProgress& progress) override
  {
    // one writer: a DEM run started on several MPI ranks runs the same model on each
    if (checkpoint_.file.empty() || dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;
    write_checkpoint(checkpoint_.file, make_checkpoint_header(checkpoint_, s.steps(), s.time()),
                     [&](dem::StateArchive& a) { visit_state(a, s, progress); });
  }

  void on_snapshot(const dem::ExplicitSolver& s) override
  {
    if (write_vtu_)
      vtu_.write(model_.particles, model_.bonds, s.time(), s.steps());
    cracks_.update(s);
    cracks_.snapshot(s.time(), s.steps());
  }

  void on_progress(const dem::ExplicitSolver& s, double fraction, double rate, double eta) override
  {
    std::printf("[%5.1f%%] step %ld, t = %.4g s, %.3g steps/s, %.3g bond-updates/s, ETA %.0f s, "
                "max speed %.3g m/s\n",
                100 * fraction, s.steps(), s.time(), rate, rate * double(model_.bonds.size()), eta,
                s.max_speed());
    std::fflush(stdout);
  }

  void finish()
  {
    history_file_.close();
    std::filesystem::rename(history_path_.string() + ".part", history_path_);
    if (write_vtu_)
      vtu_.finish();
    cracks_.finish();
  }

private:
  /// The complete state of the run for a checkpoint: the solver's, the driver's and what this
  /// observer has gathered (load histories, history.csv so far, snapshot and crack lists).
  void visit_state(dem::StateArchive& a, dem::ExplicitSolver& s, dem::RunProgress& progress)
  {
    s.visit_state(a);
    progress.visit_state(a);
    dem::StateGroup group(a, "output");
    a.io("axial_displacement", du_);
    a.io("axial_force", force_);
    a.io("axial_fixed_force", fixed_force_);
    std::vector<double> share_time, share;
    for (const auto& [t, k] : kinetic_share_)
      share_time.push_back(t), share.push_back(k);
    a.io("kinetic_share_time", share_time);
    a.io("kinetic_share", share);
    a.io("flexural_load", flex_load_);
    a.io("flexural_deflection", flex_u_);
    a.io("flexural_broken_bonds", flex_broken_);
    long history_bytes = a.loading() ? 0 : long(history_file_.durable_size());
    a.io("history_bytes", history_bytes);
    vtu_.visit_state(a);
    cracks_.visit_state(a, s);
    if (!a.loading())
      return;
    if (share_time.size() != share.size())
      throw dem::InputError(a.where() + "kinetic_share: not as long as its times");
    if (flex_broken_.size() != flex_load_.size())
      throw dem::InputError(a.where() + "flexural_broken_bonds: not as long as 'flexural_load'");
    kinetic_share_.clear();
    for (std::size_t k = 0; k < share.size(); ++k)
      kinetic_share_.emplace_back(share_time[k], share[k]);
    // history.csv as at the checkpoint, and no snapshot of the interrupted run after it
    history_file_.resume_at(history_bytes);
    remove_later_dem_snapshots(dir_, vtu_, cracks_.files());
  }

  const dem::Model& model_;
  ContactOutput contacts_{model_}; ///< contact and wall columns of history.csv
  ParticleVtuSeries vtu_;
  bool write_vtu_;
  std::filesystem::path dir_;
  std::filesystem::path history_path_;
  dem::HistoryFile history_file_;
  std::ostream& history_ = history_file_.stream();
  int fixed_ = -1, loaded_ = -1, axis_ = 0;
  std::vector<double> du_, force_, fixed_force_;
  std::vector<std::pair<double, double>> kinetic_share_;
  int pin_ = -1, roller_ = -1, top_ = -1, bottom_ = -1;
  std::vector<double> flex_load_, flex_u_;
  std::vector<std::int64_t> flex_broken_; ///< broken bonds at each flexural record
  CrackOutput cracks_;
  CheckpointSettings checkpoint_;
};
} // namespace

nlohmann::json run_dem_case(dealii::ParameterHandler& prm, const std::filesystem::path& dir,
                            CheckpointSettings checkpoint)
{
  dem::CaseConfig config = parse_dem_case(prm);
  if (!config.run.static_solver)
    check_explicit_end_time(config.run.end_time, config.particles.save_file);
  const bool failure_law = config.damage.law.mode != dem::FailureMode::none;
  // per-bond force records feed the static run's figures only (ParaView bond files evaluate
  // each bond on demand)
  config.run.bond_force_records = config.run.static_solver;
  const OutputSettings out = parse_output_settings(prm);
  checkpoint.interval = out.checkpoint_interval;
  checkpoint.wall_interval = out.checkpoint_wall_interval;
  if (config.run.static_solver && (checkpoint.enabled() || checkpoint.resume))
    throw dem::InputError(
        std::string(checkpoint.resume ? "--resume" : "Output/checkpoint interval") +
        ": the static solver has no time steps to checkpoint (explicit runs "
        "only)");
  dem::Model model = dem::build_model(config);
  if (run_dem_case_on_other_rank(config, model, checkpoint)) // mpirun -np N: rank 0 writes
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
  dem::RunResult r;
  std::vector<double> axial_du, axial_loaded, axial_fixed; // explicit runs: load history
  std::vector<double> flexural_load, flexural_u;
  std::size_t flexural_intact = 0; // records of the flexural history before the first break
  std::vector<dem::CrackEvent> cracks;
  if (config.run.static_solver)
  {
    // Simulation/static linear solver: auto = PETSc's GAMG from 150 k unknowns (where it
    // starts to beat Jacobi CG, bench/RESULTS_STATIC.md), gamg = always, cg = never.
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
    const StaticRun run = run_static_load_steps(model, config, out, dir, base);
    const dem::StaticResult& st = run.last;
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
    // the static solver is linear in the displacements and rotations (static_solver.h)
    j["geometry"] = "linear (small displacements and rotations)";
    j["max_rotation"] = dem::largest_rotation(model.particles, model.bonds);
    if (j["max_rotation"].get<double>() > max_linear_rotation)
    {
      char line[400];
      std::snprintf(line, sizeof line,
                    "max_rotation: %.3g rad: the static solver is linear (small rotations), and "
                    "its figures differ from the large-rotation solution by about half the "
                    "rotation squared (%.2g) here; Simulation/solver = explicit follows large "
                    "rotations",
                    j["max_rotation"].get<double>(),
                    0.5 * std::pow(j["max_rotation"].get<double>(), 2));
      add_warning(j, line);
    }
    add_bond_class_summary(j, model.particles, model.bonds);
    j["solver"] = {{"type", "static"},
                   {"method", st.method},
                   {"iterations", st.iterations},
                   {"residual", st.residual},
                   {"n_free_dofs", st.n_free_dofs},
                   {"held_unbonded_particles", st.held_unbonded},
                   {"assembly_seconds", st.assembly_seconds},
                   {"solve_seconds", st.solve_seconds}};
  }
  else
  {
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
    r = run_explicit_on_ranks(model, config, observer, schedule);
    observer.finish();
    axial_du = observer.axial_displacements();
    axial_loaded = observer.axial_forces(false);
    axial_fixed = observer.axial_forces(true);
    flexural_load = observer.flexural_loads();
    flexural_u = observer.flexural_deflections();
    flexural_intact = observer.flexural_records_intact();
    cracks = observer.cracks().cracks();
    if (failure_law)
      add_crack_summary(j, cracks, model.particles, model.bonds, config.measure.stress_layers,
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
        r.wall_seconds > 0 ? double(r.steps_made) * double(model.bonds.size()) / r.wall_seconds
                           : 0.0;
    j["energy"] = {{"kinetic", r.energy.kinetic},     {"strain", r.energy.strain},
                   {"damping", r.energy.damping},     {"external_work", r.energy.external},
                   {"fracture", r.energy.fracture},   {"contact_strain", r.energy.contact_strain},
                   {"friction", r.energy.friction},   {"contact_damping", r.energy.contact_damping},
                   {"wall_work", r.energy.wall_work}, {"initial", r.energy.initial}};
    j["energy_balance_error"] = r.energy_balance_error;
    j["unbalanced_force_ratio"] = r.unbalanced_force_ratio;
    ContactOutput(model).summary(j, r.time);
  }

  double mean_coordination = 0;
  for (int c : model.particles.coordination)
    mean_coordination += c;
  mean_coordination /= double(model.particles.size());

  // Particle stresses (thesis eq. 62), their histogram (Fig. 36) and slab averages (eq. 54).
  const dem::ParticleStresses stresses = dem::particle_stresses(model.particles, model.bonds);
  const auto extent = dem::reference_extent(model.particles);
  write_particle_stresses(dir / "particle_stress.csv", model.particles, stresses);
  {
    const int c = config.measure.modulus_fixed_group.empty() ? 0 : config.measure.modulus_axis;
    const auto h = dem::stress_histogram(stresses, c, config.measure.stress_histogram_bins);
    j["particle_stress_histogram"] = {{"component", std::string(2, "xyz"[c])},
                                      {"mean", h.mean},
                                      {"std_dev", h.std_dev},
                                      {"max_ratio", h.max_ratio},
                                      {"edges", h.edges},
                                      {"counts", h.counts}};
  }
  std::optional<dem::StressLayers> layers;
  if (config.measure.stress_layers > 0)
  {
    const auto& l = layers.emplace(
        dem::stress_layers(model.particles, stresses, extent.first, extent.second,
                           config.measure.stress_layer_axis, config.measure.stress_layers));
    nlohmann::json sig = nlohmann::json::array();
    for (const auto& t : l.sigma)
      sig.push_back(to_json(t));
    j["stress_layers"] = {{"axis", std::string(1, "xyz"[l.axis])},
                          {"edges", l.edges},
                          {"n_particles", l.count},
                          {"sigma", sig}};
  }
  j["strain_energy"] = stresses.strain_energy;
  if (config.measure.modulus_fixed_group.empty())
  {
    // no uniaxial test: the average over the specimen's extent (eq. 54 with V = extent volume)
    const double volume = (extent.second - extent.first).prod();
    j["rve_stress"] =
        to_json(dem::rve_average(model.particles, stresses, extent.first, extent.second, volume));
    j["rve_volume"] = volume;
  }
  j["porosity"] = model.porosity;
  j["packing_volume"] = model.packing_volume;

  j["mode"] = "dem";
  j["bond_model"] = prm.get({"Bonds"}, "model");
  j["n_particles"] = model.particles.size();
  j["n_bonds"] = model.bonds.size();
  j["mean_coordination"] = mean_coordination;
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
  {
    const auto& m = config.measure;
    const auto a = dem::axial_response(
        model.particles,
        model.groups[model.group_index(m.modulus_fixed_group, "Measurements/modulus groups")],
        model.groups[model.group_index(m.modulus_loaded_group, "Measurements/modulus groups")],
        m.modulus_axis);
    const std::string axes = "xyz";
    // a specimen that broke: its final state is past the peak (a secant through the damage),
    // so E comes from the elastic part of the curve and the final ratios keep their own names
    const bool broke = !cracks.empty();
    const std::string nu = broke ? "final_poisson_ratio_" : "poisson_ratio_";
    j[broke ? "final_secant_modulus" : "youngs_modulus"] = a.youngs_modulus;
    j["axial_stress"] = a.stress;
    j["axial_strain"] = a.strain;
    j["axial_force"] = a.force;
    j["cross_section_area"] = a.area;
    j["gauge_length"] = a.gauge_length;
    for (int d = 0; d < 3; ++d)
      if (d != a.axis)
        j[nu + axes[a.axis] + axes[d]] = a.poisson_ratio[d];
    if (a.strain == 0)
    {
      const std::string key = broke ? "final_secant_modulus" : "youngs_modulus";
      j[key] = nullptr;
      for (int d = 0; d < 3; ++d)
        if (d != a.axis)
          j[nu + axes[a.axis] + axes[d]] = nullptr;
      add_warning(j, key +
                         ": undefined, and the Poisson's ratios with it: the end groups "
                         "(Measurements/modulus groups) did not move apart along " +
                         axes[a.axis] + " (axial strain 0); written as null");
    }
    else if (a.force == 0 && !broke)
      add_warning(j, "youngs_modulus: 0: the end groups (Measurements/modulus groups) carry no "
                     "axial load (reaction 0)");
    if (axial_du.size() >= 3)
    {
      const auto& force = a.force_controlled ? axial_fixed : axial_loaded;
      // E from the elastic part of the curve (up to half the peak load) when bonds broke
      const std::size_t n_fit =
          broke ? std::max<std::size_t>(3, dem::records_before(force, 0.5)) : force.size();
      const auto fit = dem::fit_youngs_modulus({axial_du.begin(), axial_du.begin() + long(n_fit)},
                                               {force.begin(), force.begin() + long(n_fit)}, a);
      j["youngs_modulus_fit"] = fit.youngs_modulus;
      j["youngs_modulus_fit_points"] = fit.points;
      if (broke)
        j["youngs_modulus"] = fit.youngs_modulus;
      if (fit.points < 2 || fit.youngs_modulus == 0)
      {
        const std::string key = broke ? "youngs_modulus" : "youngs_modulus_fit";
        j[key] = nullptr;
        add_warning(j, key + ": undefined: the load history has no rising part to fit (" +
                           std::to_string(fit.points) + " records); written as null");
      }
      // the load transmitted through the specimen, read at the fixed end as a testing machine's
      // load cell does: the driven end's reaction also carries the local damping's drag on the
      // moving particles (5 % at the peak of tension_failure.prm), and its noise
      add_peak_stress(j, axial_fixed, axial_du, a.area, a.gauge_length);
    }
    else if (broke)
    {
      j["youngs_modulus"] = nullptr;
      add_warning(j, "youngs_modulus: undefined: bonds broke and the load history has " +
                         std::to_string(axial_du.size()) +
                         " records, too few to fit the elastic part (Output/history interval)");
    }
    // RVE = the specimen between the planes where the end loads act (gauge length x area).
    j["boundary_stress"] = a.stress;
    const dem::Tensor3 rve = dem::rve_average(model.particles, stresses, extent.first,
                                              extent.second, a.area * a.gauge_length);
    j["rve_stress"] = to_json(rve);
    j["rve_volume"] = a.area * a.gauge_length;
    j["rve_stress_asymmetry"] = (rve - rve.transpose()).norm() / std::max(rve.norm(), 1e-300);
    j["rve_stress_difference"] =
        a.stress != 0 ? std::abs(rve(a.axis, a.axis) - a.stress) / std::abs(a.stress) : 0.0;
    if (layers && a.stress != 0)
    {
      // slab averages of the loading-direction normal stress over the boundary stress (Fig. 37)
      std::vector<double> ratio;
      for (const auto& t : layers->sigma)
        ratio.push_back(t(a.axis, a.axis) / a.stress);
      j["stress_layers"]["normal_stress_ratio"] = ratio;
    }
  }
  if (!config.measure.flexural_groups.empty())
  {
    const auto& m = config.measure;
    auto group = [&](int k) -> const dem::Group& {
      return model.groups[model.group_index(m.flexural_groups[k], "Measurements/flexural groups")];
    };
    const auto f = dem::flexural_response(model.particles, group(0), group(1), group(2), group(3),
                                          0, 2, m.flexural_poisson_ratio, m.form_factor);
    j["flexural_load"] = f.load;
    j["span"] = f.span;
    j["load_length"] = f.load_length;
    j["midspan_deflection"] = f.deflection;
    j["bottom_deflection"] = f.bottom_deflection;
    if (!cracks.empty())
    {
      // past the peak the final ratio is a secant through the damage: E_f (eq. 69) from the
      // elastic part of the load-deflection curve, the records before the first bond broke (or
      // up to half the peak load when a weak bond broke earlier)
      j["final_secant_modulus"] = f.flexural_modulus;
      const std::size_t n_fit = std::max(flexural_intact, dem::records_before(flexural_load, 0.5));
      const auto fit = dem::fit_flexural_modulus(
          {flexural_u.begin(), flexural_u.begin() + long(n_fit)},
          {flexural_load.begin(), flexural_load.begin() + long(n_fit)}, f);
      j["flexural_modulus_fit_points"] = fit.points;
      j["flexural_modulus"] = fit.youngs_modulus;
      if (fit.points < 2 || fit.youngs_modulus == 0)
      {
        j["flexural_modulus"] = nullptr;
        add_warning(j, "flexural_modulus: undefined: bonds broke and the load history has no "
                       "rising part to fit (" +
                           std::to_string(fit.points) +
                           " records; Output/history interval); written as null");
      }
    }
    else if (!(f.deflection > 0))
    {
      j["flexural_modulus"] = nullptr;
      add_warning(j, "flexural_modulus: undefined: the midspan did not deflect (Measurements/"
                     "flexural groups: the loaded and bottom groups); written as null");
    }
    else
    {
      j["flexural_modulus_point_load"] = f.flexural_modulus_point;
      j["flexural_modulus"] = f.flexural_modulus;
      j["flexural_modulus_bottom"] = f.flexural_modulus_bottom;
      if (f.load == 0)
        add_warning(j, "flexural_modulus: 0: the supports (Measurements/flexural groups) carry "
                       "no load (reaction 0)");
    }
    add_peak_load(j, flexural_load, flexural_u);
  }
  if (r.natural_frequency)
    j["natural_frequency"] = *r.natural_frequency;
  else if (!config.measure.frequency_group.empty())
  {
    j["natural_frequency"] = nullptr;
    add_warning(j, "natural_frequency: undefined: group '" + config.measure.frequency_group +
                       "' (Measurements/frequency group) did not swing through its mean at least "
                       "three times in the run (a longer Simulation/end time, or less damping); "
                       "written as null");
  }
  auto& groups = j["groups"];
  for (const auto& g : model.groups)
  {
    groups[g.name]["n_particles"] = g.members.size();
    groups[g.name]["mean_displacement"] = to_json(dem::mean_displacement(model.particles, g));
    groups[g.name]["force"] = to_json(dem::total_force(model.particles, g));
  }
  return j;
}
} // namespace dembridge::app
