#pragma once
// How a command behaves when mpirun starts it on several ranks.
//
// Every rank parses the same command line and reads the same case, so most errors (bad input, a
// refusal) happen on every rank at once: the ranks agree on that (a non-blocking barrier on a
// communicator of their own), rank 0 prints the one line and every rank exits with code 1. An
// error that only some ranks meet within fail_grace_seconds is printed by the rank that met it
// and ends the whole job (MPI_Abort): no rank is ever left waiting in a collective call for a
// rank that has given up.
#include <functional>
#include <mpi.h>
#include <string>

namespace dembridge::app
{
class MpiJob
{
public:
  /// How long a failing rank waits for the other ranks to fail too before it ends the job.
  static constexpr double fail_grace_seconds = 5;

  /// Call after MPI_Init (collective: duplicates @p world for the agreement on failures).
  explicit MpiJob(MPI_Comm world);
  ~MpiJob();
  MpiJob(const MpiJob&) = delete;
  MpiJob& operator=(const MpiJob&) = delete;

  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  /// Rank 0 alone prints to the terminal.
  bool root() const { return rank_ == 0; }

  /// Progress lines of long phases that have no observer of their own (random packing:
  /// dem/core/progress.h) go to rank 0's standard output.
  void print_progress_on_root() const;

  /// Throws std::runtime_error "@p what runs on one MPI rank (@p why), this job has N; ..." when
  /// the job has more than one rank. The same on every rank, so they fail together.
  void require_one_rank(const std::string& what, const std::string& why) const;

  /// Ends a command that failed on this rank with @p line (one line, without the "dembridge:
  /// error: " prefix) and returns its exit code, 1; or, when the other ranks do not fail too
  /// within fail_grace_seconds, prints the line naming this rank and aborts the job.
  int fail(const std::string& line) const;

private:
  MPI_Comm world_, failures_ = MPI_COMM_NULL;
  int rank_ = 0, ranks_ = 1;
};

/// Runs @p work on rank 0 of @p comm only and throws its error (std::runtime_error with the same
/// message) on every rank: a collective call, so that the ranks fail together.
void on_root_for_all(MPI_Comm comm, const std::function<void()>& work);
} // namespace dembridge::app
