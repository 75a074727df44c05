#pragma once
// Checkpoint and restart of explicit DEM runs, coupled DEM-FE runs and FE dynamics runs (the
// last two on any number of MPI ranks; rank 0 alone reads and writes the file)
// (docs/checkpoint.md).
//
// A checkpoint is one HDF5 file, DIR/checkpoint.h5 in the run's output folder, written every
// Output/checkpoint interval of simulated time (or checkpoint wall interval of wall time) between
// steps: to DIR/checkpoint.h5.tmp first, flushed to the disk, then renamed over the previous one,
// so the file is always a complete checkpoint, the newest. It holds the complete state
// (dem/core/state_archive.h: particles, bonds, solver, contacts, the driver's sums; in a coupled
// run also the continuum's vectors and the tie's state) and the output so far (history.csv's
// length, dem/core/history_file.h; snapshot lists, cracks), with a header: the format and its
// version, the dembridge version, the step and time, and the case's effective parameters.
// `dembridge run CASE.prm --resume DIR` rebuilds the model from the case, refuses a checkpoint of
// another case or format version with the reason, restores the state and continues; on one thread
// the resumed run ends with the same figures as an uninterrupted one, bit for bit.
#include "dem/core/state_archive.h"
#include <deal.II/base/parameter_handler.h>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace dembridge::app
{
/// The checkpoint format this build writes and reads (docs/checkpoint.md). Version 2: rows in
/// the model's spatial order, prescribed velocities no longer stored per particle.
/// Version 3: history.csv's length at the checkpoint (`history_bytes`) instead of its text.
/// Version 4: FE dynamics runs store running summaries of their energies and zero crossings
/// instead of the series (one value a step). Version 5: every dataset carries its CRC-32
/// (attribute crc32), in HDF5's file format 1.8 (checksummed metadata); the bonds' classes
/// (`bond_class`).
inline constexpr int checkpoint_format_version = 5;
inline constexpr const char* checkpoint_format_name = "dembridge-checkpoint";

struct CheckpointSettings
{
  std::filesystem::path file; ///< DIR/checkpoint.h5 (absolute); empty: no checkpoints
  double interval = 0;        ///< simulated time between checkpoints, s; 0: none
  double wall_interval = 0;   ///< wall time between checkpoints, s; 0: none
  bool resume = false;        ///< restore from `file` before the first step
  int ranks = 1;              ///< MPI ranks of the run
  /// resume: a DEM checkpoint of the run on several ranks (distributed/run_checkpoint.h), which
  /// resumes on any number of ranks
  bool whole_run = false;
  /// resume on several ranks: a DEM checkpoint written on one rank, whose contacts are in one
  /// store's layout (read so and spread by the model's indices, distributed/run_checkpoint.h)
  bool one_rank_contacts = false;
  long resumed_step = 0; ///< the checkpoint's step and time (resume)
  double resumed_time = 0;
  std::string case_name; ///< the case file's name (messages, header)
  std::string case_text; ///< checkpoint_case_text() of this run
  bool enabled() const { return interval > 0 || wall_interval > 0; }
};

/// The checkpoint settings of `dembridge run` (the intervals are read later, from Output):
///  - --resume DIR: the run continues in DIR (@p output_dir becomes DIR; another --output-dir is
///    refused); DIR/checkpoint.h5 must be a checkpoint of this format and this case (InputError
///    with the reason otherwise);
///  - a fresh run: @p output_dir defaults to output/CASE; a folder that holds the checkpoint of
///    an interrupted run is refused (continue it with --resume, or delete the checkpoint), so
///    that days of computing are never lost to a forgotten option;
///  - a resumed checkpoint is read whole first (verify_checkpoint) and the interrupted run's
///    history file in DIR/.partial checked against it, so that a damaged or incomplete one is
///    refused before anything is built or staged;
///  - refused: checkpoints or --resume in a static FE run (FEM/problem = static: no steps;
///    InputError naming the key), a coupled or FE checkpoint of another number of MPI ranks, a
///    DEM checkpoint of one rank on several (a DEM checkpoint of several ranks resumes on any
///    number: it holds the whole run, distributed/run_checkpoint.h).
/// Collective on MPI_COMM_WORLD when MPI is running: rank 0 reads the file, every rank throws
/// its verdict.
CheckpointSettings prepare_checkpoint(const dealii::ParameterHandler& prm,
                                      const std::string& case_file, std::string& output_dir,
                                      const std::string& resume_dir);

/// After a run has committed its results: removes its checkpoint (and a .tmp a kill left).
void finish_checkpoints(const CheckpointSettings& settings);

/// The effective parameter set a checkpoint must match (provenance.h's parameters.prm text)
/// without the entries a resumed run may change: Output/checkpoint interval, Output/checkpoint
/// wall interval and Simulation/threads.
std::string checkpoint_case_text(const dealii::ParameterHandler& prm,
                                 const std::filesystem::path& case_dir);

struct CheckpointHeader
{
  long step = 0;
  double time = 0;
  int mpi_ranks = 1; ///< the run's MPI ranks (absent in older files: 1)
  std::string version, git_commit, written_at, case_name, case_text;
};

/// The header of a checkpoint this build writes now at @p step and @p time of the run that
/// @p settings describe (version, commit, UTC time, case name and text).
CheckpointHeader make_checkpoint_header(const CheckpointSettings& settings, long step, double time);

/// Reads a checkpoint's header; InputError naming the file when it is no HDF5 file, no
/// dembridge checkpoint or of another format version.
CheckpointHeader read_checkpoint_header(const std::filesystem::path& file);

/// Reads every dataset of a checkpoint and compares it with its stored checksum; InputError
/// naming the file and the damaged dataset (or the part of the file's structure HDF5 could not
/// read: HDF5 checksums its own metadata) when one differs from what was written.
void verify_checkpoint(const std::filesystem::path& file);

/// Refuses (InputError) a checkpoint whose case differs from @p case_text, naming the first
/// entries that differ with both values.
void check_same_case(const CheckpointHeader& header, const std::string& case_text,
                     const std::filesystem::path& file);

/// Writes a checkpoint atomically (file.tmp, fsync, rename): the header, then whatever
/// @p visit names. Tests: DEMBRIDGE_TEST_KILL_IN_CHECKPOINT=K kills the process (SIGKILL)
/// halfway through the K-th checkpoint this process writes.
void write_checkpoint(const std::filesystem::path& file, const CheckpointHeader& header,
                      const std::function<void(dem::StateArchive&)>& visit);

/// Restores what @p visit names from a checkpoint (read_checkpoint_header checks it first).
void read_checkpoint(const std::filesystem::path& file,
                     const std::function<void(dem::StateArchive&)>& visit);

/// A list of (time, file name) entries (ParaView series): times and the names, one per line.
void visit_file_list(dem::StateArchive& a, const std::string& name,
                     std::vector<std::pair<double, std::string>>& files);
} // namespace dembridge::app
