// dembridge: command-line front end.
//   dembridge run CASE.prm [--set "Section/Key=value"]... [--output-dir DIR]
//   dembridge print-parameters
//   dembridge verify DEM_CASE.prm [--material-from S.json | --youngs-modulus E --poisson-ratio NU]
//   dembridge elasticity DEM_CASE.prm [--set ...] [--output-dir DIR]   (elasticity.json)
//   dembridge calibrate TARGETS.prm [--set ...] [--output-dir DIR]   (calibration.json)
//   dembridge compare COUPLED_CASE.prm [--set ...] [--output-dir DIR]   (comparison.json)
// The application only parses, builds and runs; physics lives in dem/ and fem/. Each command's
// options and body live in app/cli/ and app/studies/; main parses and dispatches.
#include "app/cli/calibrate_command.h"
#include "app/cli/command_line.h"
#include "app/cli/run_command.h"
#include "app/cli/verify_command.h"
#include "app/input/case_file.h"
#include "app/job/mpi_job.h"
#include "app/job/provenance.h"
#include "app/job/version.h"
#include "app/studies/elasticity_command.h"
#include "app/studies/verify.h"
#ifdef DEMBRIDGE_HAVE_COUPLING
#include "app/studies/compare.h"
#endif
#include <CLI/CLI.hpp>
#include <deal.II/base/mpi.h>
#include <iostream>

int main(int argc, char** argv)
{
  namespace app = dembridge::app;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // under mpirun: rank 0 alone prints; an error ends the whole job (mpi_job.h)
  const app::MpiJob job(MPI_COMM_WORLD);
  app::set_command_line(argc, argv);
  job.print_progress_on_root();
  CLI::App cli{"dembridge: coupled DEM-FEM for bonded-particle models"};
  cli.require_subcommand(1);
  cli.set_version_flag("--version",
                       "dembridge " + app::version() + " (git commit " + app::git_commit() + ")");
  app::RunOptions run;
  app::add_run_command(cli, run);
  auto* print_cmd = app::add_print_parameters_command(cli);
  app::VerifyOptions verify;
  auto* verify_cmd = app::add_verify_command(cli, verify);
  app::ElasticityOptions elasticity;
  auto* elasticity_cmd = app::add_elasticity_command(cli, elasticity);
  app::CalibrateOptions calibrate;
  auto* calibrate_cmd = app::add_calibrate_command(cli, calibrate);
#ifdef DEMBRIDGE_HAVE_COUPLING
  app::CompareOptions compare;
  auto* compare_cmd = app::add_compare_command(cli, compare);
#endif
  try
  {
    cli.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    // --help and --version exit 0; a usage error is one line and exit code 1 like bad input
    if (e.get_exit_code() == 0)
      return job.root() ? cli.exit(e) : 0;
    return job.fail(app::usage_error(cli, argc, argv, e.what()) +
                    " (dembridge --help lists the usage)");
  }
  try
  {
    app::refuse_empty_paths(cli);
    if (*print_cmd)
      return app::print_parameters(job);
    // Commands that run on one rank, refused on more before they read anything.
    if (*verify_cmd)
    {
      job.require_one_rank("verify", "the FE model is small");
      return app::verify(verify);
    }
    if (*elasticity_cmd)
    {
      job.require_one_rank("elasticity", "its static solves are not shared over ranks");
      return app::run_elasticity(elasticity);
    }
    if (*calibrate_cmd)
    {
      job.require_one_rank("calibrate", "its static solves are not shared over ranks");
      return app::run_calibrate(calibrate);
    }
#ifdef DEMBRIDGE_HAVE_COUPLING
    if (*compare_cmd)
    {
      job.require_one_rank("compare", "it starts the runs itself");
      return app::run_compare(compare);
    }
#endif
    return app::run_case(job, run);
  }
  catch (const std::exception& e)
  {
    return job.fail(app::one_line(e.what()));
  }
  catch (...)
  {
    return job.fail("unknown error");
  }
}
