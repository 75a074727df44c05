#pragma once
// history.csv of an FE dynamics run: one row per step (step, time, each probe's displacement,
// the energies of the step: kinetic, kinetic shadow, strain, load potential, total and shadow
// total; fem/explicit_dynamics.h), written by rank 0. A resumed run cuts the file back to its
// checkpoint's length and appends (dem/core/history_file.h).
#include "dem/core/history_file.h"
#include "fem/fem_case.h"
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <sstream>

namespace dembridge::app
{
class FemHistory
{
public:
  /// Opens @p path on rank 0 (@p root): a fresh run's file with its header for @p n_probes
  /// probes, or a resumed run's file cut back to @p resume_length bytes (resume_length < 0: a
  /// fresh run).
  FemHistory(const std::filesystem::path& path, bool root, std::size_t n_probes,
             std::int64_t resume_length);
  /// The row of one step (rank 0).
  void add(const fem::DynamicsRow& row);
  /// The bytes written so far, on the disk: what a checkpoint records (rank 0).
  std::int64_t durable_size() { return file_.durable_size(); }
  /// Writes the last rows; a failure names the file and the reason.
  void close() { file_.close(); }

private:
  bool root_;
  dem::HistoryFile file_;
  std::ostringstream row_; ///< one row, formatted with 12 digits, reused
};

/// Writes deal.II's timer table of an FE run (fem::CaseResult::timing_table) to
/// @p dir/timing.log on rank 0 (@p root), where it stays out of the terminal's progress lines.
void write_timing_log(const std::filesystem::path& dir, const std::string& table, bool root);
} // namespace dembridge::app
