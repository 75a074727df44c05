#pragma once
// history.csv of a run that may checkpoint (app/checkpoint.h): a checkpoint records how many bytes
// of it were written, flushed to the disk first, not its text, so that a checkpoint stays the same
// size however long the run has been (one row per step would make each checkpoint, and the run's
// I/O, grow without bound). A resumed run cuts the file back to the checkpoint's length and
// appends: it then ends with the uninterrupted run's file, byte for byte.
#include "dem/core/fsync_path.h"
#include "dem/core/types.h"
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace dembridge::dem
{
class HistoryFile
{
public:
  HistoryFile() = default;
  /// Opens @p path: emptied for a fresh run; kept as it is for a resume (resume_at cuts it).
  /// @p shown is the name error messages give (the file the user knows, e.g. history.csv for
  /// history.csv.part).
  void open(const std::filesystem::path& path, bool resume, const std::string& shown = "")
  {
    path_ = path;
    shown_ = shown.empty() ? path.string() : shown;
    out_.open(path_, std::ios::binary | (resume ? std::ios::app : std::ios::trunc));
    if (!out_)
      throw std::runtime_error(shown_ + ": cannot write");
  }

  std::ofstream& stream() { return out_; }

  /// The bytes written so far, on the disk (for a checkpoint).
  std::int64_t durable_size()
  {
    out_.flush();
    if (!out_)
      throw std::runtime_error(shown_ + ": write failed");
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
      throw InputError(shown_ + ": " +
                       (ec ? std::string("missing") : std::to_string(size) + " bytes") +
                       ", but the checkpoint was written after " + std::to_string(bytes) +
                       " bytes of it: cannot resume without the run's own file");
    std::filesystem::resize_file(path_, std::uintmax_t(bytes));
    out_.open(path_, std::ios::binary | std::ios::app);
    if (!out_)
      throw std::runtime_error(shown_ + ": cannot write");
  }

  void close() { out_.close(); }

private:
  std::filesystem::path path_;
  std::string shown_;
  std::ofstream out_;
};
} // namespace dembridge::dem
