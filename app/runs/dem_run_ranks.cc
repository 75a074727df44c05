#include "app/runs/dem_run_ranks.h"
#include "app/runs/dem_static_run.h"
#include "distributed/run_explicit.h"
#include <deal.II/base/mpi.h>

namespace dembridge::app
{
namespace
{
unsigned n_ranks()
{
  return dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
}
} // namespace

bool run_dem_case_on_other_rank(const dem::CaseConfig& config, dem::Model& model,
                                const CheckpointSettings& checkpoint)
{
  if (n_ranks() == 1)
    return false;
  if (config.run.static_solver) // the solves shared by the ranks, rank 0 writes
  {
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      return false;
    solve_static_on_other_rank(model, config);
    return true;
  }
  if (checkpoint.resume)
    throw dem::InputError("--resume: DEM runs on several MPI ranks do not checkpoint yet (resume "
                          "on one rank)");
  if (checkpoint.enabled())
    throw dem::InputError("Output/checkpoint interval: DEM runs on several MPI ranks do not "
                          "checkpoint yet (set it to 0, or run on one rank)");
  if (const std::string why = distributed::unsupported_on_ranks(model); !why.empty())
    throw dem::InputError(why);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    return false;
  distributed::run_explicit(model, config, nullptr, {}, MPI_COMM_WORLD);
  return true;
}

dem::RunResult run_explicit_on_ranks(dem::Model& model, const dem::CaseConfig& config,
                                     dem::RunObserver& observer, const dem::RunSchedule& schedule)
{
  if (n_ranks() == 1)
    return dem::run_explicit(model, config, observer, schedule);
  return distributed::run_explicit(model, config, &observer, schedule, MPI_COMM_WORLD);
}
} // namespace dembridge::app
