#include "app/job/mpi_job.h"
#include "dem/core/progress.h"
#include <chrono>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <thread>

namespace dembridge::app
{
MpiJob::MpiJob(MPI_Comm world) : world_(world)
{
  MPI_Comm_rank(world_, &rank_);
  MPI_Comm_size(world_, &ranks_);
  if (ranks_ > 1)
    MPI_Comm_dup(world_, &failures_);
}

MpiJob::~MpiJob()
{
  if (failures_ != MPI_COMM_NULL)
    MPI_Comm_free(&failures_);
}

void MpiJob::print_progress_on_root() const
{
  dem::progress_sink() = [root = root()](const std::string& line)
  {
    if (root)
      std::cout << line << std::endl;
  };
}

void MpiJob::require_one_rank(const std::string& what, const std::string& why) const
{
  if (ranks_ > 1)
    throw std::runtime_error(what + " runs on one MPI rank (" + why + "), this job has " +
                             std::to_string(ranks_) + "; start it without mpirun");
}

int MpiJob::fail(const std::string& line) const
{
  if (ranks_ > 1)
  {
    // every rank that fails enters the barrier: it completes when all have failed
    MPI_Request all_failed;
    MPI_Ibarrier(failures_, &all_failed);
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(fail_grace_seconds);
    int done = 0;
    while (MPI_Test(&all_failed, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && !done &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!done)
    {
      // the others go on (or wait for this rank in a collective call): end the job
      std::fprintf(stderr, "dembridge: error: rank %d: %s\n", rank_, line.c_str());
      std::fflush(stderr);
      MPI_Abort(world_, 1);
    }
  }
  if (root())
  {
    std::fprintf(stderr, "dembridge: error: %s\n", line.c_str());
    std::fflush(stderr);
  }
  return 1;
}

void on_root_for_all(MPI_Comm comm, const std::function<void()>& work)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::string message;
  if (rank == 0)
    try
    {
      work();
    }
    catch (const std::exception& e)
    {
      message = *e.what() ? e.what() : "unknown error";
    }
  if (ranks > 1)
  {
    int size = int(message.size());
    MPI_Bcast(&size, 1, MPI_INT, 0, comm);
    message.resize(std::size_t(size));
    MPI_Bcast(message.data(), size, MPI_CHAR, 0, comm);
  }
  if (!message.empty())
    throw std::runtime_error(message);
}
} // namespace dembridge::app
