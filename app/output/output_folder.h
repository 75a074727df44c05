#pragma once
// A results folder that never shows a failed or interrupted run's files as if they were current.
//
// A run writes everything into the hidden staging folder DIR/.partial. Only when it has
// succeeded does commit() remove the previous run's files from DIR (those listed in its
// summary.json under "output_files"; for folders written before that list existed, the files
// its .pvd collections reference and dembridge's fixed file names) and move the new files in,
// summary.json last: a folder with a summary.json holds one complete run, and nothing else of
// the user's is touched. A run that fails removes its staging folder and leaves DIR exactly as
// it was (a folder it created is removed again); a killed run leaves DIR as it was plus the
// hidden .partial, which the next run clears (or, with --resume, continues: checkpoint.h). A
// resumed run that fails keeps .partial as it was, for the next --resume, and so does a run that
// fails after writing a checkpoint.
//
// While a run uses DIR it holds an exclusive lock on the folder (flock on the directory, taken
// by rank 0): a second run into DIR is refused at once. The operating system releases the lock
// when the process ends, however it ends, so a killed run never blocks the next one.
#include <filesystem>
#include <mpi.h>
#include <string>
#include <vector>

namespace dembridge::app
{
class OutputFolder
{
public:
  /// Locks @p dir, creating it if needed; refuses (std::runtime_error naming the folder) a folder
  /// that another run holds, or a path that is a file. Collective on @p comm: rank 0 does the
  /// file work, every rank throws its error.
  OutputFolder(const std::filesystem::path& dir, MPI_Comm comm);
  /// A run that was not committed: removes the staging folder (unless resumed, or a checkpoint
  /// was written) and the folder itself if this run created it and it is empty; releases the
  /// lock.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Prepares the staging folder: an empty one, clearing one left by a killed run; with
  /// @p resume the one a killed run left, which a run resumed from a checkpoint continues.
  /// Collective, as the constructor.
  void stage(bool resume);
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
  /// Removes the folders this run created, innermost first, as long as they are empty.
  void remove_created_folders() const;

  std::filesystem::path dir_, staging_;
  /// The outermost folder this run created (the folder or one above it); empty: none
  std::filesystem::path created_;
  MPI_Comm comm_;
  int lock_fd_ = -1;
  bool writer_ = false;
  bool staged_ = false, resumed_ = false, committed_ = false;
};
} // namespace dembridge::app
