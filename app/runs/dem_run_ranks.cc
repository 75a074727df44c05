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

/// On several ranks, or resuming a checkpoint written on several (which holds the contacts by
/// global ids, not in the one-rank layout; distributed/run_checkpoint.h).
bool on_ranks(const CheckpointSettings& checkpoint)
{
  return n_ranks() > 1 || (checkpoint.resume && checkpoint.whole_run);
}

distributed::Resume resume_of(const CheckpointSettings& checkpoint)
{
  return {checkpoint.resume,
          [file = checkpoint.file](const auto& visit) { read_checkpoint(file, visit); }};
}
} // namespace

bool run_dem_case_on_other_rank(const dem::CaseConfig& config, dem::Model& model,
                                const CheckpointSettings& checkpoint)
{
  if (!on_ranks(checkpoint))
    return false;
  if (config.run.static_solver) // the solves shared by the ranks, rank 0 writes
  {
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      return false;
    solve_static_on_other_rank(model, config);
    return true;
  }
  if (const std::string why =
          distributed::unsupported_on_ranks(model, checkpoint.enabled() || checkpoint.resume);
      !why.empty())
    throw dem::InputError(why);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    return false;
  distributed::run_explicit(model, config, nullptr, {}, MPI_COMM_WORLD, resume_of(checkpoint));
  return true;
}

dem::RunResult run_explicit_on_ranks(dem::Model& model, const dem::CaseConfig& config,
                                     dem::RunObserver& observer, const dem::RunSchedule& schedule,
                                     const CheckpointSettings& checkpoint)
{
  if (!on_ranks(checkpoint))
    return dem::run_explicit(model, config, observer, schedule);
  return distributed::run_explicit(model, config, &observer, schedule, MPI_COMM_WORLD,
                                   resume_of(checkpoint));
}
} // namespace dembridge::app
