#pragma once
// history.csv of a run that may checkpoint (app/checkpoint/checkpoint.h): a checkpoint records how many bytes
// of it were written, flushed to the disk first, not its text, so that a checkpoint stays the same
// size however long the run has been (one row per step would make each checkpoint, and the run's
// I/O, grow without bound). A resumed run cuts the file back to the checkpoint's length and
// appends: it then ends with the uninterrupted run's file, byte for byte.
#include "dem/core/fsync_path.h"
#include "dem/core/output_file.h"
#include "dem/core/types.h"
#include <cstdint>
#include <filesystem>
#include <string>

namespace dembridge::dem
{
class HistoryFile
{
public:
  HistoryFile() = default;
  /// Opens @p path: emptied for a fresh run; kept as it is for a resume (resume_at cuts it),
  /// which needs the interrupted run's file (InputError naming it when it is missing). Errors
  /// name the file and the system's reason (output_file.h).
  void open(const std::filesystem::path& path, bool resume)
  {
    path_ = path;
    if (resume && !std::filesystem::exists(path_))
      missing(-1);
    out_.open(path_, std::ios::binary | (resume ? std::ios::app : std::ios::trunc));
  }

  std::ostream& stream() { return out_; }

  /// The bytes written so far, on the disk (for a checkpoint).
  std::int64_t durable_size()
  {
    out_.flush();
    fsync_path(path_);
    return std::int64_t(std::filesystem::file_size(path_));
  }

  /// Cuts the file back to the @p bytes a checkpoint recorded (rows written after it go) and
  /// appends from there. Throws InputError if the file is shorter: it is not the checkpoint's.
  void resume_at(std::int64_t bytes)
  {
    out_.close(); // why: whatever the stream holds is written first, then cut off
    std::error_code ec;
    const auto size = std::filesystem::file_size(path_, ec);
    if (ec || bytes < 0 || std::int64_t(size) < bytes)
      missing(ec ? -1 : std::int64_t(size), bytes);
    std::filesystem::resize_file(path_, std::uintmax_t(bytes));
    out_.open(path_, std::ios::binary | std::ios::app);
  }

  /// Writes what is buffered and closes; throws naming the file if any write failed.
  void close() { out_.close(); }

private:
  /// Refuses a resume whose file is missing (@p size < 0) or shorter than the checkpoint's
  /// @p bytes, naming the file by its full path.
  [[noreturn]] void missing(std::int64_t size, std::int64_t bytes = -1) const
  {
    const std::string file = std::filesystem::absolute(path_).lexically_normal().string();
    if (bytes < 0)
      throw InputError(file + ": missing: the checkpoint continues this file of the interrupted "
                              "run; cannot resume without it");
    throw InputError(file + ": " +
                     (size < 0 ? std::string("missing") : std::to_string(size) + " bytes") +
                     ", but the checkpoint was written after " + std::to_string(bytes) +
                     " bytes of it: cannot resume without the run's own file");
  }

  std::filesystem::path path_;
  OutputFile out_;
};
} // namespace dembridge::dem
