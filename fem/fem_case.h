// dembridge::fem — the entry point the app calls for "set Mode = fem".
#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include "parameters.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace dembridge::dem
{
class StateArchive; // dem/core/state_archive.h
}

namespace dembridge::fem
{
/// Declare every FEM parameter subsection (FEM, FEM/Mesh, FEM/Material, ...), each entry with a
/// default, a bounded pattern and a documentation string.
void declare_parameters(dealii::ParameterHandler& prm);

/// Checkpoints of an explicit dynamics run (docs/checkpoint.md). The app layer owns the file:
/// the run calls write() between steps when one is due (simulated-time interval, or wall-time
/// interval by rank 0's clock) and read() once before its first step when it resumes, handing
/// over a visit of its complete state (the continuum's /fe/ and the run's /fem_run/: history
/// rows, energy series, zero crossings, the next checkpoint time). Rank 0 alone calls write()
/// and read(); the run gathers the state to it and spreads it from it (collective).
struct DynamicsCheckpoints
{
  using Visit = std::function<void(dem::StateArchive&)>;
  double interval = 0;      ///< s of simulated time; 0: none
  double wall_interval = 0; ///< s of wall time; 0: none
  bool resume = false;
  std::function<void(long step, double time, const Visit&)> write;
  std::function<void(const Visit&)> read;
  std::function<void(long step)> after_step; ///< called after every step (tests); may be empty
};

/// Removes the continuum snapshots in @p dir that a run interrupted after its last checkpoint
/// wrote (they are written again on resume): BASE_NNNN.pvtu and its pieces BASE_NNNN.R.vtu not
/// among the restored @p records (time, file name). Used by FE and coupled resumes alike.
void remove_later_fe_snapshots(const std::filesystem::path& dir, const std::string& base,
                               const std::vector<std::pair<double, std::string>>& records);

/// Run the case described by @p prm (already parsed): static elasticity or explicit dynamics.
/// Writes ParaView files (.vtu/.pvtu/.pvd) and history.csv (dynamics) into @p output_dir and
/// returns the summary (SI units, snake_case keys). Throws std::runtime_error with a one-line
/// message naming the parameter ("Section/Key") or file on bad input.
/// @p checkpoints (dynamics only; null: none) checkpoints the run or resumes it.
nlohmann::json run_case(const dealii::ParameterHandler& prm,
                        const std::filesystem::path& output_dir, MPI_Comm comm,
                        const DynamicsCheckpoints* checkpoints = nullptr);
/// The same for parameters built in code (coupling/full_models.h).
nlohmann::json run_case(const Parameters& p, const std::filesystem::path& output_dir, MPI_Comm comm,
                        const DynamicsCheckpoints* checkpoints = nullptr);
} // namespace dembridge::fem
