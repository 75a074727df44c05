#pragma once
// A DEM run (Mode = dem) under `mpirun -np N` with N > 1: the explicit solver's time stepping
// spread over the ranks on deal.II's particle handler (distributed/, docs/parallel.md). Every
// rank reads the case and builds the same model; rank 0 runs the usual observer and summary
// over the whole model, the other ranks step their parts and write their particles' and bonds'
// pieces of each snapshot (ParticlePieces). Checkpoints are written by rank 0
// with the whole run's state and resume on any number of ranks (distributed/run_checkpoint.h).
#include "app/checkpoint/checkpoint.h"
#include "app/output/particle_vtu.h"
#include "dem/model/model.h"
#include "dem/solvers/run_explicit.h"
#include <nlohmann/json.hpp>

namespace dembridge::app
{
/// Call on every rank once the model is built. On one rank (unless it resumes a checkpoint
/// written on several): false. On several: throws (on
/// every rank alike) what cannot run there yet; then a rank other than 0 steps its part of
/// the run and returns true (its caller is done), rank 0 returns false and goes on to
/// run_explicit_on_ranks.
/// @p dir, @p write_vtu: where and whether the snapshots are written (on several ranks each rank
/// writes its own particles and the bonds it books: ParticlePieces).
bool run_dem_case_on_other_rank(const dem::CaseConfig& config, dem::Model& model,
                                const CheckpointSettings& checkpoint,
                                const std::filesystem::path& dir, bool write_vtu);

/// dem::run_explicit, on as many ranks as the run has (distributed also on one rank when it
/// resumes a checkpoint written on several). @p snapshots: the observer's ParaView series (null:
/// none written); on several ranks its particles and bonds are written in pieces into @p dir.
/// Adds to @p summary, on any number of ranks alike (so that one rank's summary has the keys of
/// N ranks'): mpi_ranks, n_repartitions (the rebuilds that repartitioned the mesh, since the
/// resume in a resumed run), repartition_imbalance_max_before and _after (the largest
/// imbalance, most owned particles over their mean, that started a repartition and that one
/// left; 0 without any, as on one rank).
dem::RunResult run_explicit_on_ranks(dem::Model& model, const dem::CaseConfig& config,
                                     dem::RunObserver& observer, const dem::RunSchedule& schedule,
                                     const CheckpointSettings& checkpoint,
                                     const std::filesystem::path& dir, ParticleVtuSeries* snapshots,
                                     nlohmann::json& summary);
} // namespace dembridge::app
