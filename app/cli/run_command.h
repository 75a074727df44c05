#pragma once
// dembridge run CASE [--set "Section/Key=value"]... [--output-dir DIR] [--resume DIR]: reads the
// case, runs it in its mode (dem, fem, coupled) inside the staged output folder
// (app/output/output_folder.h), and writes summary.json (the run's figures, its warnings, the
// memory estimate and the provenance) and parameters.prm; prints the figures.
#include "app/job/mpi_job.h"
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace dembridge::app
{
struct RunOptions
{
  std::string case_file;
  std::vector<std::string> overrides; ///< --set "Section/Key=value"
  std::string output_dir;             ///< empty: output/<case stem>
  std::string resume_dir;             ///< --resume: the interrupted run's folder
};

/// Declares the subcommand and its options on @p app.
CLI::App* add_run_command(CLI::App& app, RunOptions& options);

/// Runs the case; returns the exit code (errors are thrown, naming the case file).
int run_case(const MpiJob& job, const RunOptions& options);
} // namespace dembridge::app
