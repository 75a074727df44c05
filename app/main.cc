// dembridge: command-line front end.
//   dembridge run CASE.prm [--set "Section/Key=value"]... [--output-dir DIR]
//   dembridge print-parameters
//   dembridge verify DEM_CASE.prm [--material-from S.json | --youngs-modulus E --poisson-ratio NU]
//   dembridge elasticity DEM_CASE.prm [--set ...] [--output-dir DIR]   (elasticity.json)
//   dembridge compare COUPLED_CASE.prm [--set ...] [--output-dir DIR]   (comparison.json)
// The application only parses, builds and runs; physics lives in dem/ and fem/.
#include "app/checkpoint/checkpoint.h"
#include "app/input/case_file.h"
#include "app/job/mpi_job.h"
#include "app/job/provenance.h"
#include "app/job/version.h"
#include "app/output/output_folder.h"
#include "app/output/result_warnings.h"
#include "app/runs/dem_run.h"
#include "app/runs/memory_guard.h"
#include "app/studies/elasticity_command.h"
#include "app/studies/verify.h"
#include "dem/core/output_file.h"
#include "dem/core/progress.h"
#include "dem/core/types.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "fem/fem_case.h"
#endif
#ifdef DEMBRIDGE_HAVE_COUPLING
#include "app/runs/coupled_run.h"
#include "app/studies/compare.h"
#endif
#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <deal.II/base/mpi.h>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace
{
/// Writes summary.json atomically (temporary file, then rename): a reader never sees half a
/// summary, and a failed run leaves none.
void write_summary(const fs::path& dir, const nlohmann::json& j)
{
  const fs::path tmp = dir / "summary.json.part";
  {
    dembridge::dem::OutputFile out(tmp); // failures name the file and the reason
    out << j.dump(2) << '\n';
    out.close();
  }
  fs::rename(tmp, dir / "summary.json");
}

/// One line for a command-line error; an unknown subcommand is named with the known ones.
std::string usage_error(CLI::App& app, int argc, char** argv, const std::string& what)
{
  if (argc > 1 && argv[1][0] != '-')
  {
    std::string known;
    bool found = false;
    for (const auto* sub : app.get_subcommands({}))
    {
      known += (known.empty() ? "" : ", ") + sub->get_name();
      found = found || sub->get_name() == argv[1];
    }
    if (!found)
      return "unknown subcommand '" + std::string(argv[1]) + "' (expected " + known + ")";
  }
  return dembridge::app::one_line(what);
}

#ifdef DEMBRIDGE_HAVE_FEM
/// An FE dynamics run's checkpoints (fem_case.h) on the checkpoint file of @p checkpoint.
dembridge::fem::DynamicsCheckpoints fem_checkpoints(const dealii::ParameterHandler& prm,
                                                    const dembridge::app::CheckpointSettings& c)
{
  dembridge::fem::DynamicsCheckpoints f;
  if (c.file.empty())
    return f;
  f.interval = prm.get_double({"Output"}, "checkpoint interval");
  f.wall_interval = prm.get_double({"Output"}, "checkpoint wall interval");
  f.resume = c.resume;
  f.write = [&c](long step, double time, const dembridge::fem::DynamicsCheckpoints::Visit& visit)
  { dembridge::app::write_checkpoint(c.file, make_checkpoint_header(c, step, time), visit); };
  f.read = [&c](const dembridge::fem::DynamicsCheckpoints::Visit& visit)
  {
    dembridge::app::read_checkpoint(c.file, visit);
    std::printf("resumed from %s: step %ld, t = %.6g s\n", c.file.string().c_str(), c.resumed_step,
                c.resumed_time);
  };
  if (const char* kill = std::getenv("DEMBRIDGE_TEST_KILL_AFTER_STEP")) // tests (checkpoint.h)
    f.after_step = [step = std::atol(kill)](long n)
    {
      if (n == step)
        std::raise(SIGKILL);
    };
  return f;
}
#endif

/// A folder option given an empty path would silently fall back to the default folder.
void refuse_empty_paths(const CLI::App& app)
{
  for (const auto* command : app.get_subcommands())
    for (const char* name : {"--output-dir", "--resume"})
      if (const auto* option = command->get_option_no_throw(name);
          option && option->count() > 0 && option->as<std::string>().empty())
        throw std::runtime_error(std::string(name) + ": the path is empty (name a folder" +
                                 (name == std::string("--output-dir")
                                      ? ", or leave the option out for the default one)"
                                      : ")"));
}

int run(const dembridge::app::MpiJob& job, const std::string& case_file,
        const std::vector<std::string>& overrides, std::string output_dir,
        const std::string& resume_dir)
{
  const auto start = std::chrono::steady_clock::now();
  const std::string started_at = dembridge::app::utc_now();
  auto prm = dembridge::app::read_case(case_file, overrides);
  const std::string mode = prm->get("Mode");
  // Mode = dem on several ranks: explicit runs split the particles over the ranks (rank 0
  // writes); what does not run there yet is refused on every rank alike (dem_run_ranks.h).
  // Paths inside the case (particle files, meshes) are relative to the case file.
  const fs::path case_dir = fs::absolute(case_file).parent_path();
  // The folder (prepare_checkpoint's rule: --resume's, --output-dir, or output/CASE) is locked
  // before anything looks into it: a second run into it is refused first, whatever it holds.
  const fs::path dir = !resume_dir.empty()   ? fs::path(resume_dir)
                       : !output_dir.empty() ? fs::path(output_dir)
                                             : fs::path("output") / fs::path(case_file).stem();
  dembridge::app::OutputFolder folder(dir, MPI_COMM_WORLD);
  // --resume DIR continues the run in DIR from DIR/checkpoint.h5 (checkpoint.h)
  const dembridge::app::CheckpointSettings checkpoint =
      dembridge::app::prepare_checkpoint(*prm, case_file, output_dir, resume_dir);
  // Written into a staging folder and moved in on success (output_folder.h): a failed or killed
  // run leaves the previous run's complete results, never a mix; a resumed run keeps the staged
  // files of the run it continues.
  folder.stage(checkpoint.resume);
  nlohmann::json summary, memory_estimate;
  const fs::path abs_dir = folder.staging();
  const fs::path cwd = fs::current_path();
  fs::current_path(case_dir);
  try
  {
    // a continuum has no bonds: strengths there would be silently unused
    if (mode == "fem" && prm->get({"Damage"}, "failure") != "none")
      throw std::runtime_error("Damage/failure: a continuum run (Mode = fem) has no bonds to "
                               "break; damage needs particles (Mode = dem, or coupled with the "
                               "damage zone in its particle region)");
    // before building anything: refuse a case the machine's memory cannot hold
    memory_estimate = dembridge::app::check_memory(*prm);
    // tests: one rank fails alone while the others go on into collective calls (mpi_job.h)
    if (const char* rank = std::getenv("DEMBRIDGE_TEST_FAIL_ON_RANK");
        rank && std::atoi(rank) == job.rank())
      throw std::runtime_error("DEMBRIDGE_TEST_FAIL_ON_RANK: this rank fails alone");
    if (mode == "dem")
      summary = dembridge::app::run_dem_case(*prm, abs_dir, checkpoint);
    else if (mode == "coupled")
    {
#ifdef DEMBRIDGE_HAVE_COUPLING
      summary = dembridge::app::run_coupled_case(*prm, abs_dir, MPI_COMM_WORLD, checkpoint);
#else
      throw std::runtime_error("Mode: this build has no coupling layer (deal.II not found)");
#endif
    }
    else
    {
#ifdef DEMBRIDGE_HAVE_FEM
      {
        const auto fem_checkpoint = fem_checkpoints(*prm, checkpoint);
        summary = dembridge::fem::run_case(*prm, abs_dir, MPI_COMM_WORLD, &fem_checkpoint);
        if (checkpoint.resume)
          summary["resumed_from"] = {{"file", checkpoint.file.string()},
                                     {"step", checkpoint.resumed_step},
                                     {"time", checkpoint.resumed_time}};
      }
#else
      throw std::runtime_error("Mode: this build has no FEM layer (deal.II not found)");
#endif
    }
  }
  catch (const dembridge::dem::InputError& e)
  {
    // name the file: the message already names the key and the reason
    fs::current_path(cwd);
    throw std::runtime_error(fs::path(case_file).filename().string() + ": " + e.what());
  }
  catch (const std::runtime_error& e)
  {
    // FE input errors (std::runtime_error naming Section/key) name the file as DEM errors do
    fs::current_path(cwd);
    const std::string name = fs::path(case_file).filename().string();
    const std::string what = e.what();
    throw std::runtime_error(what.rfind(name, 0) == 0 ? what : name + ": " + what);
  }
  catch (...)
  {
    fs::current_path(cwd);
    throw;
  }
  fs::current_path(cwd);
  // a figure the run could not measure is named in "warnings", never a silent null
  dembridge::app::flag_undefined_figures(
      summary, dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);
  summary["case"] = fs::path(case_file).filename().string();
  summary["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary["memory_estimate"] = memory_estimate;
  summary["peak_memory_bytes"] = dembridge::app::peak_memory_bytes();
  summary.update(dembridge::app::provenance(*prm, started_at));
  dembridge::app::on_root_for_all(MPI_COMM_WORLD,
                                  [&]
                                  {
                                    dembridge::app::write_parameters_file(
                                        *prm, case_file, abs_dir / "parameters.prm");
                                    auto files = folder.staged_files();
                                    files.push_back("summary.json");
                                    summary["output_files"] = files;
                                    write_summary(abs_dir, summary);
                                  });
  folder.commit();
  if (job.root())
  {
    dembridge::app::finish_checkpoints(checkpoint); // the run is complete: no checkpoint left
    dembridge::app::print_figures(summary, std::cout);
    std::cout << "dembridge: wrote " << (dir / "summary.json").string() << '\n';
  }
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // under mpirun: rank 0 alone prints; an error ends the whole job (mpi_job.h)
  const dembridge::app::MpiJob job(MPI_COMM_WORLD);
  dembridge::app::set_command_line(argc, argv);
  // long phases without an observer (random packing) report here (dem/core/progress.h)
  dembridge::dem::progress_sink() = [root = job.root()](const std::string& line)
  {
    if (root)
      std::cout << line << std::endl;
  };
  CLI::App app{"dembridge: coupled DEM-FEM for bonded-particle models"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "dembridge " + dembridge::app::version() + " (git commit " +
                                        dembridge::app::git_commit() + ")");
  std::string case_file, output_dir;
  std::vector<std::string> overrides;
  auto* run_cmd = app.add_subcommand("run", "Run a case file (.prm or .json)");
  run_cmd->add_option("case", case_file, "Case file")->required();
  run_cmd->add_option("--set", overrides, "Override a parameter: \"Section/Key=value\"");
  run_cmd->add_option("--output-dir", output_dir, "Output folder (default output/CASE)");
  std::string resume_dir;
  run_cmd->add_option("--resume", resume_dir,
                      "Continue the interrupted run in this output folder from its checkpoint "
                      "(Output/checkpoint interval; docs/checkpoint.md)");
  auto* print_cmd = app.add_subcommand("print-parameters",
                                       "Print every parameter with its default and documentation");
  dembridge::app::VerifyOptions verify;
  auto* verify_cmd = app.add_subcommand(
      "verify", "Run a DEM specimen case and the FE model of the same specimen; compare them");
  verify_cmd->add_option("case", verify.case_file, "DEM case file (uniaxial or bending test)")
      ->required();
  verify_cmd->add_option("--set", verify.overrides, "Override a parameter: \"Section/Key=value\"");
  verify_cmd->add_option("--output-dir", verify.output_dir,
                         "Output folder (default output/verify_CASE)");
  auto* from = verify_cmd->add_option("--material-from", verify.material_from,
                                      "summary.json of a uniaxial DEM test (E, mean nu) or "
                                      "an elasticity.json (its stiffness tensor)");
  auto* e_opt = verify_cmd->add_option("--youngs-modulus", verify.youngs_modulus, "E (Pa)");
  auto* nu_opt = verify_cmd->add_option("--poisson-ratio", verify.poisson_ratio, "nu");
  verify_cmd->add_option("--shear-modulus", verify.shear_modulus,
                         "G (Pa): cubic FE material along the axes, C44 = G (default isotropic)");
  e_opt->needs(nu_opt)->excludes(from);
  nu_opt->needs(e_opt);
  verify_cmd->add_option("--dem-run", verify.dem_run,
                         "Folder of a finished DEM run of this case (its summary.json is used)");
  verify_cmd->add_flag("!--no-plot", verify.plot, "Do not write comparison.png");
  verify_cmd
      ->add_flag("--measured-tensor", verify.measured_tensor,
                 "FE material: the stiffness tensor measured on the case's own packing")
      ->excludes(from)
      ->excludes(e_opt);
  dembridge::app::ElasticityOptions elasticity;
  auto* elasticity_cmd = dembridge::app::add_elasticity_command(app, elasticity);
#ifdef DEMBRIDGE_HAVE_COUPLING
  dembridge::app::CompareOptions compare;
  auto* compare_cmd = dembridge::app::add_compare_command(app, compare);
#endif
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    // --help and --version exit 0; a usage error is one line and exit code 1 like bad input
    if (e.get_exit_code() == 0)
      return job.root() ? app.exit(e) : 0;
    return job.fail(usage_error(app, argc, argv, e.what()) + " (dembridge --help lists the usage)");
  }
  try
  {
    refuse_empty_paths(app);
    if (*print_cmd)
    {
      dealii::ParameterHandler prm;
      dembridge::app::declare_all_parameters(prm, {"<name>"}, {"<name>"}, {"<name>"});
      if (job.root())
        prm.print_parameters(std::cout, dealii::ParameterHandler::Text);
      return 0;
    }
    // Commands that run on one rank, refused on more before they read anything.
    if (*verify_cmd)
    {
      job.require_one_rank("verify", "the FE model is small");
      return dembridge::app::verify(verify);
    }
    if (*elasticity_cmd)
    {
      job.require_one_rank("elasticity", "the static solver is serial");
      return dembridge::app::run_elasticity(elasticity);
    }
#ifdef DEMBRIDGE_HAVE_COUPLING
    if (*compare_cmd)
    {
      job.require_one_rank("compare", "it starts the runs itself");
      return dembridge::app::run_compare(compare);
    }
#endif
    return run(job, case_file, overrides, output_dir, resume_dir);
  }
  catch (const std::exception& e)
  {
    return job.fail(dembridge::app::one_line(e.what()));
  }
  catch (...)
  {
    return job.fail("unknown error");
  }
}
