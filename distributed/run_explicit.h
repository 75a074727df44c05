#pragma once
// dem::run_explicit on several MPI ranks: the same stop criteria, records, snapshots and
// measurements, the model's time stepping spread over the ranks (distributed_solver.h). Every
// rank calls it with the same model and case; the observer is rank 0's only and reads rank 0's
// report solver over the whole model, which holds what a one-rank run's solver would (the
// figures summed over the ranks at each record, the particles of the groups gathered at each
// record and every particle and bond state at snapshots and at the end), so that the history,
// ParaView files and summary a one-rank observer writes come out the same.
// Not yet on several ranks (the caller refuses them): checkpoints, contacts and walls (forces
// beside the bonds), the static solver, more than 32 groups.
#include "dem/solvers/run_explicit.h"
#include <deal.II/base/mpi.h>

namespace dembridge::distributed
{
/// Collective. @p observer: rank 0's (ignored elsewhere); @p schedule: rank 0's is used. On
/// return rank 0's model holds the final state; the other ranks' model has given up its
/// particles and bonds (each rank kept only its part after the setup).
dem::RunResult run_explicit(dem::Model& model, const dem::CaseConfig& config,
                            dem::RunObserver* observer, dem::RunSchedule schedule, MPI_Comm comm);

/// Why a model cannot run on several ranks yet (empty: it can).
std::string unsupported_on_ranks(const dem::Model& model);
} // namespace dembridge::distributed
