#pragma once
// A results folder that never shows a failed or interrupted run's files as if they were current.
//
// A run writes everything into the hidden staging folder DIR/.partial. Only when it has
// succeeded does commit() remove the previous run's files from DIR (those listed in its
// summary.json under "output_files"; for folders written before that list existed, the files
// its .pvd collections reference and dembridge's fixed file names) and move the new files in,
// summary.json last: a folder with a summary.json holds one complete run, and nothing else of
// the user's is touched. A run that fails removes its staging folder and leaves DIR exactly as
// it was; a killed run leaves DIR as it was plus the hidden .partial, which the next run clears
// (or, with --resume, continues: checkpoint.h).
#include <filesystem>
#include <mpi.h>
#include <string>
#include <vector>

namespace dembridge::app
{
class OutputFolder
{
public:
  /// Creates @p dir and an empty staging folder in it (clearing one left by a killed run). With
  /// several MPI ranks, rank 0 does the file work and the others wait for it. @p resume keeps
  /// the staging folder a killed run left: a run resumed from a checkpoint continues it.
  OutputFolder(const std::filesystem::path& dir, MPI_Comm comm, bool resume = false);
  /// Removes the staging folder unless the run was committed.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Absolute path of the staging folder: every file of the run is written here.
  const std::filesystem::path& staging() const { return staging_; }
  /// The final folder.
  const std::filesystem::path& folder() const { return dir_; }
  /// Names (relative to the staging folder) of the files staged so far, sorted.
  std::vector<std::string> staged_files() const;
  /// Replaces the previous run's files in the folder by the staged ones (summary.json last)
  /// and removes the staging folder. Call on every rank, after every rank has written.
  void commit();

  /// The previous run's files in @p dir: summary.json's "output_files" when present, else the
  /// fixed names dembridge writes and the files the .pvd/.pvtu collections there reference.
  static std::vector<std::string> previous_results(const std::filesystem::path& dir);

private:
  std::filesystem::path dir_, staging_;
  MPI_Comm comm_;
  bool writer_ = false;
  bool committed_ = false;
};
} // namespace dembridge::app
