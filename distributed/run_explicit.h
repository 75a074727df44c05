#pragma once
// dem::run_explicit on several MPI ranks: the same stop criteria, records, snapshots and
// measurements, the model's time stepping spread over the ranks (distributed_solver.h). Every
// rank calls it with the same model and case; the observer is rank 0's only and reads rank 0's
// report solver over the whole model, which holds what a one-rank run's solver would (the
// figures summed over the ranks and the crack log at each record, the particles of the groups
// gathered at each record, every particle and bond state at the end, and at snapshots too
// unless the ranks write them in pieces: SnapshotPieces, each rank its own particles and the
// bonds it books), so that the history, ParaView files and summary a one-rank observer writes
// come out the same.
// Checkpoints as on one rank (RunSchedule), written collectively: every rank gathers the run's
// state into rank 0's report solver at the same step (run_checkpoint.h), rank 0's observer
// writes it, and every rank learns whether the write failed (and then throws its error). A
// checkpoint so written holds the whole run, and resumes on any number of ranks.
// Not yet on several ranks (unsupported_on_ranks): the contact monitor, more than 32 groups,
// smooth joints (weak-plane or basal); the static solver (the caller refuses it).
#include "dem/solvers/run_explicit.h"
#include "distributed/bond_piece.h"
#include <deal.II/base/mpi.h>
#include <functional>

namespace dembridge::distributed
{
/// A resumed run: the ranks other than 0 read the checkpoint with @p read (rank 0's observer
/// reads it in on_start).
struct Resume
{
  bool resume = false;
  /// Calls the visit with the checkpoint's archive.
  std::function<void(const std::function<void(dem::StateArchive&)>&)> read;
  /// The checkpoint was written by a run on one rank: its contacts are in one store's layout.
  bool one_rank_contacts = false;
};

/// Writes a snapshot in pieces, on every rank (collective): the first @p n_owned particles of
/// the rank's store (owned ones; ghosts after them, @p b the rank's bonds, for their stress),
/// and the bonds the rank books (@p bonds).
using SnapshotPieces =
    std::function<void(const dem::ParticleStore& p, std::size_t n_owned, const dem::BondStore& b,
                       const BondPiece& bonds, double time, long step)>;

/// How the ranks shared the run's particles (the same on every rank): the rebuilds that
/// repartitioned the mesh and, over them, the largest imbalance (most owned particles / their
/// mean) that started one and the largest left after one (0, 0 without any;
/// DistributedParticles::repartition_imbalance). A resumed run's since its resume.
struct RanksReport
{
  long n_repartitions = 0;
  double imbalance_max_before = 0;
  double imbalance_max_after = 0;
};

/// Collective. @p observer: rank 0's (ignored elsewhere); @p schedule: rank 0's is used.
/// @p pieces (every rank passes one, or none): at each snapshot, before rank 0's observer
/// writes the rest of it (then the whole state is not gathered at snapshots). On
/// return rank 0's model holds the final state; the other ranks' model has given up its
/// particles and bonds (each rank kept only its part after the setup). @p ranks (optional):
/// how the ranks shared the particles.
dem::RunResult run_explicit(dem::Model& model, const dem::CaseConfig& config,
                            dem::RunObserver* observer, dem::RunSchedule schedule, MPI_Comm comm,
                            const Resume& resume = {}, const SnapshotPieces& pieces = {},
                            RanksReport* ranks = nullptr);

/// Why a model cannot run on several ranks yet (empty: it can).
std::string unsupported_on_ranks(const dem::Model& model);
} // namespace dembridge::distributed
