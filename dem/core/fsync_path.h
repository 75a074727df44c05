#pragma once
// Flushes a file's data (or a folder's entries) to the disk: fsync through a descriptor of its
// own, which on Linux (POSIX) flushes the file whatever stream wrote it. Best effort: a path that
// cannot be opened is left alone (the write that follows reports real trouble).
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

namespace dembridge::dem
{
inline void fsync_path(const std::filesystem::path& path)
{
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0)
    return;
  ::fsync(fd);
  ::close(fd);
}
} // namespace dembridge::dem
