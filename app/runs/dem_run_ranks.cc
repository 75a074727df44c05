#include "app/runs/dem_run_ranks.h"
#include "app/runs/dem_static_run.h"
#include "distributed/run_explicit.h"
#include <deal.II/base/mpi.h>
#include <memory>

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
          [file = checkpoint.file](const auto& visit) { read_checkpoint(file, visit); },
          checkpoint.one_rank_contacts};
}
/// On several ranks: every rank writes its particles' and its bonds' pieces of each snapshot
/// (ParticlePieces).
distributed::SnapshotPieces pieces_of(const dem::Model& model, const std::filesystem::path& dir,
                                      bool write_vtu, ParticleVtuSeries* series)
{
  if (!write_vtu || n_ranks() < 2)
    return {};
  auto pieces = std::make_shared<ParticlePieces>(dir, group_names(model), MPI_COMM_WORLD, series);
  return [pieces](const dem::ParticleStore& p, std::size_t n_owned, const dem::BondStore& b,
                  const distributed::BondPiece& bonds, double time, long step)
  {
    pieces->write(p, n_owned, b, time, step);
    pieces->write_bonds(bonds.ends, bonds.bonds, bonds.ids, bonds.classes, time, step);
  };
}
} // namespace

bool run_dem_case_on_other_rank(const dem::CaseConfig& config, dem::Model& model,
                                const CheckpointSettings& checkpoint,
                                const std::filesystem::path& dir, bool write_vtu)
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
  if (const std::string why = distributed::unsupported_on_ranks(model); !why.empty())
    throw dem::InputError(why);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    return false;
  distributed::run_explicit(model, config, nullptr, {}, MPI_COMM_WORLD, resume_of(checkpoint),
                            pieces_of(model, dir, write_vtu, nullptr));
  return true;
}

dem::RunResult run_explicit_on_ranks(dem::Model& model, const dem::CaseConfig& config,
                                     dem::RunObserver& observer, const dem::RunSchedule& schedule,
                                     const CheckpointSettings& checkpoint,
                                     const std::filesystem::path& dir, ParticleVtuSeries* snapshots,
                                     nlohmann::json& summary)
{
  distributed::RanksReport ranks;
  dem::RunResult result =
      on_ranks(checkpoint)
          ? distributed::run_explicit(
                model, config, &observer, schedule, MPI_COMM_WORLD, resume_of(checkpoint),
                pieces_of(model, dir, snapshots != nullptr, snapshots), &ranks)
          : dem::run_explicit(model, config, observer, schedule);
  summary["mpi_ranks"] = n_ranks();
  summary["n_repartitions"] = ranks.n_repartitions;
  summary["repartition_imbalance_max_before"] = ranks.imbalance_max_before;
  summary["repartition_imbalance_max_after"] = ranks.imbalance_max_after;
  return result;
}
} // namespace dembridge::app
