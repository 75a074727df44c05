#include "app/runs/coupled_run.h"
#include "app/input/coupled_parameters.h"
#include "app/input/dem_parameters.h"
#include "app/job/provenance.h"
#include "app/job/version.h"
#include "app/output/coupled_figures.h"
#include "app/output/crack_output.h"
#include "app/output/particle_vtu.h"
#include "app/output/result_warnings.h"
#include "coupling/measurements.h"
#include "dem/core/history_file.h"
#include "dem/core/output_file.h"
#include "dem/measurements/measurements.h"
#include "fem/fem_case.h"

#include <deal.II/base/mpi.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <sstream>

namespace dembridge::app
{
namespace
{
using coupling::CoupledProblem;

/// Runs @p work on rank 0 only; its exception is thrown on every rank (an InputError as one), so
/// that no rank waits in a collective call for a rank that has given up.
void on_root(MPI_Comm comm, const std::function<void()>& work)
{
  std::string message;
  bool input = false;
  if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    try
    {
      work();
    }
    catch (const dem::InputError& e)
    {
      message = e.what(), input = true;
    }
    catch (const std::exception& e)
    {
      message = *e.what() ? e.what() : "unknown error";
    }
  if (dealii::Utilities::MPI::n_mpi_processes(comm) > 1)
  {
    message = dealii::Utilities::MPI::broadcast(comm, message, 0);
    input = dealii::Utilities::MPI::broadcast(comm, input, 0);
  }
  if (message.empty())
    return;
  if (input)
    throw dem::InputError(message);
  throw std::runtime_error(message);
}

/// history.csv, the ParaView series of both sides and progress lines.
class CoupledObserver : public coupling::CoupledRunObserver
{
public:
  CoupledObserver(const std::filesystem::path& dir, const OutputSettings& out,
                  CoupledProblem& problem, std::vector<fem::PointProbe>& probes, bool root,
                  const CheckpointSettings& checkpoint, bool failure_law)
      : dir_(dir), write_vtu_(out.write_vtu), probes_(probes), root_(root), vtu_(dir),
        cracks_(dir, out.write_vtu, failure_law), checkpoint_(checkpoint)
  {
    // the load a testing machine would read: the first prescribed motion's group, the force
    // the prescription exerts on it (its reaction, ExplicitSolver::group_force) along the
    // motion, and its displacement along it
    for (const auto& l : problem.model().loads)
      if (l.prescribes_motion() && l.value.norm() > 0 && load_group_ < 0)
        load_group_ = l.group, load_direction_ = l.value.normalized();
    // without one, the continuum's reaction (FEM/Measurements/reaction boundary, along the
    // reaction direction) against the loaded boundary's approach (e.g. a specimen compressed
    // through its FE ends: both positive in compression); every rank (collective)
    const auto& fp = problem.fe_parameters();
    if (load_group_ < 0 && !fp.reaction_boundary.empty() && !fp.loaded_boundary.empty())
    {
      auto& cont = problem.continuum();
      fe_reaction_id_ = fem::find_boundary(cont.boundary_names(), fp.reaction_boundary,
                                           "FEM/Measurements/reaction boundary");
      fe_loaded_id_ = fem::find_boundary(cont.boundary_names(), fp.loaded_boundary,
                                         "FEM/Measurements/loaded boundary");
      fe_direction_ = fp.reaction_direction;
      fe_load_ = true;
    }
    if (!root_)
      return;
    // A resume keeps the interrupted run's file; visit_state cuts it back to the checkpoint.
    history_file_.open(dir / "history.csv.part", checkpoint.resume);
    history_ << std::setprecision(10);
    if (checkpoint.resume)
      return;
    history_ << "step,time,dem_kinetic_energy,dem_strain_energy,dem_damping_energy,"
                "dem_external_work,dem_other_energy,fe_kinetic_energy,fe_strain_energy,"
                "fe_damping_energy,fe_boundary_work,multiplier_work_particles,"
                "multiplier_work_fe,energy_balance_error,max_tie_gap,n_broken_bonds,"
                "band_failure_index,load,load_displacement";
    for (const auto& g : problem.model().groups)
      for (const char* q : {"ux", "uy", "uz"})
        history_ << ',' << g.name << '_' << q;
    for (std::size_t k = 0; k < probes_.size(); ++k)
      for (const char* q : {"ux", "uy", "uz"})
        history_ << ",fe_probe" << k << '_' << q;
    if (problem.adaptive_region()) // the region as it stands; a growth's jump on the next row
      history_ << ",region_cells,n_particles,n_bonds,region_growth_events,growth_energy_jump";
    history_ << '\n' << std::setprecision(10);
  }

  void on_start(CoupledProblem& problem, coupling::CoupledRunProgress& progress) override
  {
    // refused before the first step, not at the first checkpoint (the particles are rank 0's)
    if (checkpoint_.enabled() || checkpoint_.resume)
      on_root(problem.communicator(),
              [&]
              {
                if (!problem.particle_solver()->checkpointable())
                  throw dem::InputError("Output/checkpoint interval: this run has forces on the "
                                        "particles that cannot be checkpointed yet");
              });
    if (!checkpoint_.resume)
      return;
    // rank 0 reads the file; every rank then takes its part of the continuum and the rest
    on_root(problem.communicator(),
            [&]
            {
              read_checkpoint(checkpoint_.file,
                              [&](dem::StateArchive& a) { visit_state(a, problem, progress); });
            });
    problem.scatter_state();
    fem::broadcast_state(problem.communicator(),
                         [&](dem::StateArchive& a)
                         {
                           progress.visit_state(a);
                           int cycle = int(cycle_);
                           a.io("cycle", cycle);
                           cycle_ = unsigned(cycle);
                         });
    first_step_ = problem.steps();
    if (!root_)
      return;
    std::printf("resumed from %s: step %ld, t = %.6g s\n", checkpoint_.file.string().c_str(),
                problem.steps(), problem.time());
    std::fflush(stdout);
  }

  void on_checkpoint(CoupledProblem& problem, coupling::CoupledRunProgress& progress) override
  {
    if (checkpoint_.file.empty())
      return;
    problem.gather_state(); // collective: the continuum's parts to rank 0, which writes
    on_root(problem.communicator(),
            [&]
            {
              write_checkpoint(checkpoint_.file,
                               make_checkpoint_header(checkpoint_, problem.steps(), problem.time()),
                               [&](dem::StateArchive& a) { visit_state(a, problem, progress); });
            });
  }

  void on_record(const CoupledProblem& problem) override
  {
    std::vector<dealii::Tensor<1, 3>> u;
    for (const auto& p : probes_) // collective
      u.push_back(const_cast<CoupledProblem&>(problem).continuum().probe_vector(p));
    double fe_load = 0, fe_approach = 0;
    if (fe_load_) // collective
    {
      const auto& cont = const_cast<CoupledProblem&>(problem).continuum();
      fe_load = cont.reaction(fe_reaction_id_) * fe_direction_;
      fe_approach = -(cont.boundary_means(fe_loaded_id_).mean_displacement -
                      cont.boundary_means(fe_reaction_id_).mean_displacement) *
                    fe_direction_;
    }
    if (!root_)
      return;
    const auto& e = problem.energies();
    history_ << problem.steps() << ',' << problem.time() << ',' << e.dem_kinetic << ','
             << e.dem_strain << ',' << e.dem_damping << ',' << e.dem_external << ',' << e.dem_other
             << ',' << e.fe_kinetic << ',' << e.fe_strain << ',' << e.fe_damping << ','
             << e.fe_boundary_work << ',' << e.multiplier_work_particles << ','
             << e.multiplier_work_fe << ',' << e.balance_error() << ',' << problem.max_tie_gap()
             << ',' << problem.particle_solver()->n_broken_bonds() << ','
             << problem.band_damage().max_failure_index;
    {
      const auto* s = problem.particle_solver();
      const double load = load_group_ >= 0 ? s->group_force(load_group_).dot(load_direction_) : 0.0;
      const double u =
          load_group_ >= 0 ? s->group_mean_displacement(load_group_).dot(load_direction_) : 0.0;
      if (fe_load_)
        history_ << ',' << fe_load << ',' << fe_approach;
      else
        history_ << ',' << load << ',' << u;
      if (load_group_ >= 0)
        load_.push_back(load), load_displacement_.push_back(u);
      else if (fe_load_)
        load_.push_back(fe_load), load_displacement_.push_back(fe_approach);
    }
    cracks_.update(*problem.particle_solver());
    auto& model = const_cast<CoupledProblem&>(problem).model();
    for (const auto& g : model.groups)
    {
      const dem::Vec3 d = dem::mean_displacement(model.particles, g);
      history_ << ',' << d.x() << ',' << d.y() << ',' << d.z();
    }
    for (const auto& v : u)
      history_ << ',' << v[0] << ',' << v[1] << ',' << v[2];
    if (const auto* a = problem.adaptive_region())
    {
      const auto& events = problem.growth_events();
      double jump = 0; // of the growths since the last row
      for (std::size_t k = events_written_; k < events.size(); ++k)
        jump += events[k].energy_jump();
      events_written_ = events.size();
      history_ << ',' << a->n_region_cells() << ',' << model.particles.size() << ','
               << model.bonds.size() << ',' << events.size() << ',' << jump;
    }
    history_ << '\n';
  }

  /// The continuum is a new mesh after a growth: its probes are made anew (collective).
  void on_region_growth(CoupledProblem& problem, const coupling::GrowthEvent&) override
  {
    for (auto& probe : probes_)
      probe = problem.continuum().make_probe(probe.point, "FEM/Measurements/deflection points");
  }

  void on_snapshot(CoupledProblem& problem) override
  {
    if (!write_vtu_)
      return;
    const std::string fe_file = problem.output_results(dir_, cycle_++); // collective
    if (!root_)
      return;
    vtu_.write(problem.model().particles, problem.model().bonds, problem.time(), problem.steps());
    fe_files_.emplace_back(problem.time(), fe_file);
    cracks_.update(*problem.particle_solver());
    cracks_.snapshot(problem.time(), problem.steps());
  }

  void on_progress(const CoupledProblem& problem, double fraction, double rate, double eta) override
  {
    if (!root_)
      return;
    std::printf("[%5.1f%%] step %ld, t = %.4g s, %.3g steps/s, ETA %.0f s, energy balance "
                "%.2e, coupling %.0f %% of the time\n",
                100 * fraction, problem.steps(), problem.time(), rate, eta,
                problem.energies().balance_error(),
                // the wall time of this process's steps (a resumed run's since its checkpoint)
                100 * problem.coupling_seconds() /
                    std::max(1e-12, double(problem.steps() - first_step_) / rate));
    std::fflush(stdout);
  }

  /// Closes history.csv and writes particles.pvd, bonds.pvd (fem.pvd is the FE side's) and
  /// coupled.pvd: every part at every snapshot time, for ParaView to open as one.
  const std::vector<dem::CrackEvent>& cracks() const { return cracks_.cracks(); }
  /// Load history of the first prescribed motion, else of the continuum's reaction boundary
  /// (empty without either).
  const std::vector<double>& loads() const { return load_; }
  const std::vector<double>& load_displacements() const { return load_displacement_; }

  void finish()
  {
    if (!root_)
      return;
    history_file_.close();
    std::filesystem::rename(dir_ / "history.csv.part", dir_ / "history.csv");
    cracks_.finish();
    if (!write_vtu_)
      return;
    vtu_.finish();
    dem::OutputFile pvd(dir_ / "coupled.pvd"); // failures name the file and the reason
    pvd << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n"
        << std::setprecision(12);
    const auto& particles = vtu_.particle_files();
    const auto& bonds = vtu_.bond_files();
    for (std::size_t k = 0; k < fe_files_.size(); ++k)
    {
      const double t = fe_files_[k].first;
      auto entry = [&](int part, const std::string& file, const char* name)
      {
        pvd << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"" << part << "\" name=\""
            << name << "\" file=\"" << file << "\"/>\n";
      };
      if (k < particles.size())
        entry(0, particles[k].second, "particles");
      if (k < bonds.size())
        entry(1, bonds[k].second, "bonds");
      entry(2, fe_files_[k].second, "continuum");
    }
    pvd << "  </Collection>\n</VTKFile>\n";
    pvd.close();
  }

private:
  /// The complete state of the run for a checkpoint (rank 0, at the file; on_start and
  /// on_checkpoint hand the other ranks their parts): the problem's, the loop's and what this
  /// observer has gathered (history.csv so far, the load history, the snapshot lists of both
  /// sides, the crack output).
  void visit_state(dem::StateArchive& a, CoupledProblem& problem,
                   coupling::CoupledRunProgress& progress)
  {
    problem.visit_state(a);
    if (a.loading() && problem.adaptive_region()) // the continuum may be the grown region's
      for (auto& probe : probes_)
        probe = problem.continuum().make_probe(probe.point, "FEM/Measurements/deflection points");
    progress.visit_state(a);
    dem::StateGroup group(a, "output");
    a.io("load", load_);
    a.io("load_displacement", load_displacement_);
    if (a.loading() && load_.size() != load_displacement_.size())
      throw dem::InputError(a.where() + "load: not as long as 'load_displacement'");
    if (problem.adaptive_region()) // the growths whose jumps history.csv holds
      a.io("growth_events_written", events_written_);
    long history_bytes = a.loading() ? 0 : long(history_file_.durable_size());
    a.io("history_bytes", history_bytes);
    vtu_.visit_state(a);
    {
      dem::StateGroup fe(a, "fe_snapshots");
      int cycle = int(cycle_);
      a.io("cycle", cycle);
      cycle_ = unsigned(cycle);
      visit_file_list(a, "fe", fe_files_);
    }
    cracks_.visit_state(a, *problem.particle_solver());
    if (!a.loading())
      return;
    // history.csv as at the checkpoint, and no snapshot of the interrupted run after it
    history_file_.resume_at(history_bytes);
    remove_later_dem_snapshots(dir_, vtu_, cracks_.files());
    fem::remove_later_fe_snapshots(dir_, problem.fe_parameters().base_name, fe_files_);
  }

  std::filesystem::path dir_;
  bool write_vtu_;
  std::vector<fem::PointProbe>& probes_;
  bool root_;
  ParticleVtuSeries vtu_;
  CrackOutput cracks_;
  dem::HistoryFile history_file_;
  std::ostream& history_ = history_file_.stream();
  unsigned int cycle_ = 0;
  std::size_t events_written_ = 0; ///< growth events accounted for in history.csv
  long first_step_ = 0; ///< the step this process started at (a resumed run's checkpoint's)
  std::vector<std::pair<double, std::string>> fe_files_;
  int load_group_ = -1;
  dem::Vec3 load_direction_ = dem::Vec3::UnitZ();
  bool fe_load_ = false; ///< the load is the continuum's reaction (no particle load)
  dealii::types::boundary_id fe_reaction_id_ = 0, fe_loaded_id_ = 0;
  dealii::Tensor<1, 3> fe_direction_;
  std::vector<double> load_, load_displacement_;
  CheckpointSettings checkpoint_;
};

/// Refuses a case whose continuum supports, driven faces, loads or measurement faces name a
/// boundary with no face left: the particle region covers it and its cells were cut out
/// (coupled_mesh.h), so what acts there would act on nothing (collective).
void check_boundaries_have_faces(const coupling::CoupledCase& c, CoupledProblem& p)
{
  std::vector<std::pair<std::string, std::string>> used; // boundary, key
  for (const auto& b : c.continuum.boundary_constraints)
    used.emplace_back(b.boundary, "FEM/Boundary conditions/boundaries");
  for (const auto& d : c.settings.driven)
    used.emplace_back(d.boundary, "FEM/Boundary conditions/boundaries");
  for (const auto& l : c.continuum.boundary_forces)
    used.emplace_back(l.boundary, "FEM/Loads/boundary forces");
  for (const auto& l : c.continuum.tractions)
    used.emplace_back(l.boundary, "FEM/Loads/tractions");
  if (!c.continuum.reaction_boundary.empty())
    used.emplace_back(c.continuum.reaction_boundary, "FEM/Measurements/reaction boundary");
  if (!c.continuum.loaded_boundary.empty())
    used.emplace_back(c.continuum.loaded_boundary, "FEM/Measurements/loaded boundary");
  auto& cont = p.continuum();
  for (const auto& [name, key] : used)
  {
    const auto id = fem::find_boundary(cont.boundary_names(), name, key);
    if (cont.boundary_means(id).area > 0)
      continue;
    const auto& g = c.settings.geometry;
    std::ostringstream s;
    s << key << ": boundary '" << name
      << "' has no face left in the continuum: the particle region (" << g.particle_lo.x() << ", "
      << g.particle_lo.y() << ", " << g.particle_lo.z() << " to " << g.particle_hi.x() << ", "
      << g.particle_hi.y() << ", " << g.particle_hi.z()
      << ") covers it, and the continuum is cut out there, so nothing would act or be measured "
         "on it (move the particle region off that face, or load and measure the particles)";
    throw dem::InputError(s.str());
  }
}
} // namespace

nlohmann::json run_coupled_case(dealii::ParameterHandler& prm, const std::filesystem::path& dir,
                                MPI_Comm comm, CheckpointSettings checkpoint)
{
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  coupling::CoupledCase c = parse_coupled_case(prm);
  check_explicit_end_time(c.particles.run.end_time);
  const bool failure_law = c.particles.damage.law.mode != dem::FailureMode::none;
  const OutputSettings out = parse_output_settings(prm);
  // checkpoints hold the particles as rank 0 steps them (coupled_state.cc); a resumed run
  // reads one
  if (out.checkpoint_interval > 0 || out.checkpoint_wall_interval > 0 || checkpoint.resume)
    c.settings.particles_on_rank0 = "Output/checkpoint interval: checkpoints (and --resume)";
  auto problem = coupling::make_coupled_problem(c, comm);
  coupling::CoupledRunSettings run = parse_coupled_run_settings(prm, c);
  if (!checkpoint.file.empty()) // prepare_checkpoint: not an FE run
  {
    run.checkpoint_interval = checkpoint.interval = out.checkpoint_interval;
    run.checkpoint_wall_interval = checkpoint.wall_interval = out.checkpoint_wall_interval;
  }
  if (const char* kill = std::getenv("DEMBRIDGE_TEST_KILL_AFTER_STEP")) // tests (checkpoint.h)
    run.kill_after_step = std::atol(kill);
  CoupledProblem& p = *problem;
  const auto& fe = p.continuum();
  if (root)
  {
    std::printf("coupled: %zu particles (%zu tied in the band), %zu bonds; continuum %u cells, "
                "%llu DoFs; time step %.4g s (particle region's own %.4g s, continuum %.4g s)\n",
                p.n_particles(), p.n_interface_particles(), p.model().bonds.size(),
                unsigned(fe.n_cells()), (unsigned long long)fe.n_dofs(), p.time_step(),
                p.particle_time_step(), p.fe_time_step());
    if (p.particle_layout() != "one process")
      std::printf("coupled: the particle region steps on %s%s%s\n",
                  p.particle_layout() == "ranks" ? "the MPI ranks (distributed particle layer)"
                                                 : "rank 0",
                  p.particle_layout_reason().empty() ? "" : "; not on the ranks: ",
                  p.particle_layout_reason().c_str());
    std::fflush(stdout);
  }
  std::vector<fem::PointProbe> probes;
  for (const auto& x : c.continuum.deflection_points)
    probes.push_back(p.continuum().make_probe(x, "FEM/Measurements/deflection points"));

  check_boundaries_have_faces(c, p);
  nlohmann::json j;
  j["warnings"] = nlohmann::json::array(); // rank 0's (the particle model's)
  on_root(comm, [&]
          { check_bond_coverage(p.model().particles, p.model().bonds.size(), c.particles, j); });
  if (root)
    for (const auto& w : coupling::damage_setup_warnings(c, p))
      add_warning(j, w);

  CoupledObserver observer(dir, out, p, probes, root, checkpoint, failure_law);
  const coupling::CoupledRunResult r = coupling::run_coupled(p, run, observer);
  observer.finish();

  add_coupled_run_figures(j, p, r);
  j["mpi_ranks"] = dealii::Utilities::MPI::n_mpi_processes(comm);
  j["particle_region_steps_on"] = p.particle_layout(); // "ranks", "rank 0", "one process"
  if (!p.particle_layout_reason().empty())
    j["particle_region_on_rank0_because"] = p.particle_layout_reason();
  if (checkpoint.resume)
    j["resumed_from"] = {{"file", checkpoint.file.string()},
                         {"step", checkpoint.resumed_step},
                         {"time", checkpoint.resumed_time}};
  add_band_figures(j, p, c, r);
  // FE probes (collective) and the particle groups (rank 0, broadcast)
  add_fe_probe_figures(j, p, c, probes);
  add_fe_reaction_figures(j, p, c, root);
  std::string groups_text;
  if (root)
    groups_text = particle_region_figures(p, c, failure_law, observer.cracks(), observer.loads(),
                                          observer.load_displacements())
                      .dump();
  groups_text = dealii::Utilities::MPI::broadcast(comm, groups_text, 0);
  j.update(nlohmann::json::parse(groups_text));
  return j;
}
} // namespace dembridge::app
