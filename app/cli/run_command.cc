#include "app/cli/run_command.h"
#include "app/checkpoint/checkpoint.h"
#include "app/cli/case_folder.h"
#include "app/input/case_file.h"
#include "app/job/provenance.h"
#include "app/output/output_folder.h"
#include "app/output/result_warnings.h"
#include "app/runs/dem_run.h"
#include "app/runs/memory_guard.h"
#include "dem/core/output_file.h"
#include "dem/core/types.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "app/runs/fem_checkpoints.h"
#include "app/runs/fem_run.h"
#endif
#ifdef DEMBRIDGE_HAVE_COUPLING
#include "app/runs/coupled_run.h"
#endif
#include <chrono>
#include <cstdlib>
#include <deal.II/base/mpi.h>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace dembridge::app
{
namespace
{
/// Writes summary.json atomically (temporary file, then rename): a reader never sees half a
/// summary, and a failed run leaves none.
void write_summary(const fs::path& dir, const nlohmann::json& j)
{
  const fs::path tmp = dir / "summary.json.part";
  {
    dem::OutputFile out(tmp); // failures name the file and the reason
    out << j.dump(2) << '\n';
    out.close();
  }
  fs::rename(tmp, dir / "summary.json");
}

/// The run in the case's mode, in the case's folder; its summary.
nlohmann::json run_mode(const MpiJob& job, dealii::ParameterHandler& prm, const fs::path& abs_dir,
                        const CheckpointSettings& checkpoint, nlohmann::json& memory_estimate)
{
  const std::string mode = prm.get("Mode");
  // a continuum has no bonds: strengths there would be silently unused
  if (mode == "fem" && prm.get({"Damage"}, "failure") != "none")
    throw std::runtime_error("Damage/failure: a continuum run (Mode = fem) has no bonds to "
                             "break; damage needs particles (Mode = dem, or coupled with the "
                             "damage zone in its particle region)");
  // before building anything: refuse a case the machine's memory cannot hold
  memory_estimate = check_memory(prm);
  // tests: one rank fails alone while the others go on into collective calls (mpi_job.h)
  if (const char* rank = std::getenv("DEMBRIDGE_TEST_FAIL_ON_RANK");
      rank && std::atoi(rank) == job.rank())
    throw std::runtime_error("DEMBRIDGE_TEST_FAIL_ON_RANK: this rank fails alone");
  if (mode == "dem")
    return run_dem_case(prm, abs_dir, checkpoint);
  if (mode == "coupled")
  {
#ifdef DEMBRIDGE_HAVE_COUPLING
    return run_coupled_case(prm, abs_dir, MPI_COMM_WORLD, checkpoint);
#else
    throw std::runtime_error("Mode: this build has no coupling layer (deal.II not found)");
#endif
  }
#ifdef DEMBRIDGE_HAVE_FEM
  const auto fem_checkpoint = fem_checkpoints(prm, checkpoint);
  nlohmann::json summary =
      run_fem_case(fem::parse_parameters(prm), abs_dir, MPI_COMM_WORLD, &fem_checkpoint);
  if (checkpoint.resume)
    summary["resumed_from"] = {{"file", checkpoint.file.string()},
                               {"step", checkpoint.resumed_step},
                               {"time", checkpoint.resumed_time}};
  return summary;
#else
  throw std::runtime_error("Mode: this build has no FEM layer (deal.II not found)");
#endif
}

/// Writes parameters.prm and summary.json (listing the run's files) into the staging folder.
void write_results(const dealii::ParameterHandler& prm, const std::string& case_file,
                   const OutputFolder& folder, nlohmann::json& summary)
{
  const fs::path abs_dir = folder.staging();
  on_root_for_all(MPI_COMM_WORLD,
                  [&]
                  {
                    write_parameters_file(prm, case_file, abs_dir / "parameters.prm");
                    auto files = folder.staged_files();
                    files.push_back("summary.json");
                    summary["output_files"] = files;
                    write_summary(abs_dir, summary);
                  });
}
} // namespace

CLI::App* add_run_command(CLI::App& app, RunOptions& o)
{
  auto* run_cmd = app.add_subcommand("run", "Run a case file (.prm or .json)");
  run_cmd->add_option("case", o.case_file, "Case file")->required();
  run_cmd->add_option("--set", o.overrides, "Override a parameter: \"Section/Key=value\"");
  run_cmd->add_option("--output-dir", o.output_dir, "Output folder (default output/CASE)");
  run_cmd->add_option("--resume", o.resume_dir,
                      "Continue the interrupted run in this output folder from its checkpoint "
                      "(Output/checkpoint interval; docs/checkpoint.md)");
  return run_cmd;
}

int run_case(const MpiJob& job, const RunOptions& o)
{
  const auto start = std::chrono::steady_clock::now();
  const std::string started_at = utc_now();
  auto prm = read_case(o.case_file, o.overrides);
  // Mode = dem on several ranks: explicit runs split the particles over the ranks (rank 0
  // writes); what does not run there yet is refused on every rank alike (dem_run_ranks.h).
  // The folder (prepare_checkpoint's rule: --resume's, --output-dir, or output/CASE) is locked
  // before anything looks into it: a second run into it is refused first, whatever it holds.
  const fs::path dir = !o.resume_dir.empty()   ? fs::path(o.resume_dir)
                       : !o.output_dir.empty() ? fs::path(o.output_dir)
                                               : fs::path("output") / fs::path(o.case_file).stem();
  OutputFolder folder(dir, MPI_COMM_WORLD);
  // --resume DIR continues the run in DIR from DIR/checkpoint.h5 (checkpoint.h)
  std::string output_dir = o.output_dir; // prepare_checkpoint may fill it in
  const CheckpointSettings checkpoint =
      prepare_checkpoint(*prm, o.case_file, output_dir, o.resume_dir);
  // Written into a staging folder and moved in on success (output_folder.h): a failed or killed
  // run leaves the previous run's complete results, never a mix; a resumed run keeps the staged
  // files of the run it continues.
  folder.stage(checkpoint.resume);
  nlohmann::json memory_estimate;
  // in the case's folder (paths inside the case are relative to it); errors name the case file
  nlohmann::json summary = in_case_folder(
      o.case_file,
      [&] { return run_mode(job, *prm, folder.staging(), checkpoint, memory_estimate); });
  // a figure the run could not measure is named in "warnings", never a silent null
  flag_undefined_figures(summary, dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);
  summary["case"] = fs::path(o.case_file).filename().string();
  summary["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary["memory_estimate"] = memory_estimate;
  summary["peak_memory_bytes"] = peak_memory_bytes();
  summary.update(provenance(*prm, started_at));
  write_results(*prm, o.case_file, folder, summary);
  folder.commit();
  if (job.root())
  {
    finish_checkpoints(checkpoint); // the run is complete: no checkpoint left
    print_figures(summary, std::cout);
    std::cout << "dembridge: wrote " << (dir / "summary.json").string() << '\n';
  }
  return 0;
}
} // namespace dembridge::app
