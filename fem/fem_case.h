// dembridge::fem — the entry point the app calls for "set Mode = fem" (and for the FE models of
// verify and compare): runs and measures a case; the caller, told of the solved state and of
// every step, writes the files (app/runs/fem_run.h).
#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include "explicit_dynamics.h"
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

/// One row of an explicit dynamics run's history: step n, its time t_n, the probes'
/// displacements u_n (FEM/Dynamics/probe points) and the energies of step n.
struct DynamicsRow
{
  unsigned int step = 0;
  double time = 0;
  const std::vector<dealii::Tensor<1, 3>>& probe_displacements;
  const ExplicitDynamics::Energies& energies;
};

/// Where a dynamics run starts: fresh (no step done) or resumed from a checkpoint.
struct DynamicsStart
{
  std::size_t n_probes = 0;
  long steps_done = 0;
  bool resumed = false;
  long history_length = 0; ///< a resumed run: the caller's history length at its checkpoint
};

/// The caller's hooks while an FE case runs: the run measures, the caller decides what to write,
/// when and where (app/runs/fem_run.h). Every rank is called; field output is collective.
class CaseObserver
{
public:
  virtual ~CaseObserver() = default;
  /// A static run: the solved continuum, after its figures are measured.
  virtual void on_solved(ElasticProblem&) {}
  /// A dynamics run, before its first step (a resumed run's state already restored).
  virtual void on_dynamics_start(ExplicitDynamics&, const DynamicsStart&) {}
  /// A dynamics run, after each step.
  virtual void on_step(ExplicitDynamics&, const DynamicsRow&) {}
  /// The caller's history length, kept in a checkpoint and handed back on resume (rank 0).
  virtual long history_length() { return 0; }
  /// A dynamics run, after its last step.
  virtual void on_dynamics_end(ExplicitDynamics&) {}
};

/// What an FE case run measured.
struct CaseResult
{
  nlohmann::json figures;   ///< the summary's figures (SI units, snake_case keys)
  std::string timing_table; ///< deal.II's wall-time statistics of the run's phases (rank 0)
};

/// Run the case @p p: static elasticity or explicit dynamics, on the ranks of @p comm. Writes
/// no file: @p observer hears of the solved state and of every step. Throws
/// std::runtime_error with a one-line message naming the parameter ("Section/Key") or file on
/// bad input. @p checkpoints (dynamics only; null: none) checkpoints the run or resumes it.
CaseResult run_case(const Parameters& p, MPI_Comm comm, CaseObserver& observer,
                    const DynamicsCheckpoints* checkpoints = nullptr);

/// Writes the continuum's fields (displacement, strain, stress, von Mises stress and the cell
/// fields the problem carries) into @p dir: a .vtu per rank and a .pvtu as snapshot @p cycle at
/// @p time, and the .pvd (FEM/Output/base name) over every snapshot so far (collective).
void write_fields(ElasticProblem& problem, const std::filesystem::path& dir, unsigned int cycle,
                  double time);
} // namespace dembridge::fem
