#include "app/output/output_folder.h"
#include "app/job/mpi_job.h"
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <stdexcept>
#include <sys/file.h>
#include <unistd.h>

namespace dembridge::app
{
namespace fs = std::filesystem;

namespace
{
bool is_rank0(MPI_Comm comm)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank == 0;
}

/// The files a ParaView collection (.pvd: file="...", .pvtu: Source="...") references.
std::vector<std::string> referenced_files(const fs::path& collection)
{
  std::ifstream in(collection);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  static const std::regex reference(R"re((?:file|Source)="([^"/\\]+)")re");
  std::vector<std::string> files;
  for (std::sregex_iterator m(text.begin(), text.end(), reference), end; m != end; ++m)
    files.push_back((*m)[1]);
  return files;
}

/// An exclusive lock on the folder @p dir for as long as the returned descriptor is open (the
/// process's end closes it); refuses a folder another process holds.
int lock_folder(const fs::path& dir)
{
  // why O_CLOEXEC: a program this run starts (the comparison plot) must not inherit the lock
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0)
    throw std::runtime_error(dir.string() + ": cannot open the output folder (" +
                             std::strerror(errno) + ")");
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0)
    return fd;
  const int error = errno;
  if (error == EWOULDBLOCK)
  {
    ::close(fd);
    throw std::runtime_error(dir.string() +
                             ": another dembridge run is using this output folder (wait for it "
                             "to end, or choose another --output-dir)");
  }
  // a file system without locks (some network mounts): the run goes on, unprotected, and says so
  std::fprintf(stderr,
               "dembridge: warning: %s: the output folder cannot be locked (%s): a second run "
               "into it would not be refused\n",
               dir.c_str(), std::strerror(error));
  return fd;
}
} // namespace

OutputFolder::OutputFolder(const fs::path& dir, MPI_Comm comm)
    : dir_(fs::absolute(dir).lexically_normal()), comm_(comm), writer_(is_rank0(comm))
{
  if (dir_.filename().empty()) // a path given with a trailing separator
    dir_ = dir_.parent_path();
  staging_ = dir_ / ".partial";
  on_root_for_all(comm_,
                  [&]
                  {
                    if (fs::exists(dir_) && !fs::is_directory(dir_))
                      throw std::runtime_error(dir_.string() + ": the output folder is a file");
                    fs::path outermost_missing;
                    for (fs::path p = dir_; !fs::exists(p) && p != p.parent_path();
                         p = p.parent_path())
                      outermost_missing = p;
                    fs::create_directories(dir_);
                    created_ = outermost_missing;
                    try
                    {
                      lock_fd_ = lock_folder(dir_);
                    }
                    catch (...)
                    {
                      remove_created_folders();
                      throw;
                    }
                  });
}

OutputFolder::~OutputFolder()
{
  if (writer_ && !committed_)
  {
    // A run that wrote a checkpoint before it failed keeps its staged files: --resume
    // continues from that checkpoint and needs them (a fresh run into the folder is refused
    // while the checkpoint is there).
    std::error_code ignored;
    if (staged_ && !resumed_ && !fs::exists(dir_ / "checkpoint.h5", ignored))
      fs::remove_all(staging_, ignored);
    remove_created_folders();
  }
  if (lock_fd_ >= 0)
    ::close(lock_fd_);
}

void OutputFolder::remove_created_folders() const
{
  // only while empty: a failed run leaves what it wrote beside them (a checkpoint) in place
  if (created_.empty())
    return;
  std::error_code error;
  for (fs::path p = dir_; fs::remove(p, error) && p != created_; p = p.parent_path())
  {
  }
}

void OutputFolder::stage(bool resume)
{
  staged_ = true;
  resumed_ = resume;
  on_root_for_all(comm_,
                  [&]
                  {
                    if (!resume)
                      fs::remove_all(staging_); // left by a killed run
                    fs::create_directories(staging_);
                  });
}

std::vector<std::string> OutputFolder::staged_files() const
{
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(staging_))
    if (entry.is_regular_file())
      names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> OutputFolder::previous_results(const fs::path& dir)
{
  std::set<std::string> files;
  const fs::path summary = dir / "summary.json";
  if (fs::is_regular_file(summary))
  {
    std::ifstream in(summary);
    const auto j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (j.is_object() && j.contains("output_files") && j["output_files"].is_array())
    {
      for (const auto& f : j["output_files"])
        if (f.is_string() && fs::path(f.get<std::string>()).filename() == f.get<std::string>())
          files.insert(f.get<std::string>());
      files.insert("summary.json");
      return {files.begin(), files.end()};
    }
  }
  // A folder written before the list: dembridge's fixed names and the ParaView series.
  for (const char* name : {"summary.json", "summary.json.part", "parameters.prm", "history.csv",
                           "history.csv.part", "particle_stress.csv", "particle_stress.csv.part",
                           "cracks.csv", "comparison.csv", "comparison.png"})
    files.insert(name);
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().extension() == ".pvd" && entry.is_regular_file())
      {
        files.insert(entry.path().filename().string());
        for (const auto& f : referenced_files(entry.path()))
        {
          files.insert(f);
          if (fs::path(f).extension() == ".pvtu")
            for (const auto& piece : referenced_files(dir / f))
              files.insert(piece);
        }
      }
  return {files.begin(), files.end()};
}

void OutputFolder::commit()
{
  MPI_Barrier(comm_); // every rank has written its files
  on_root_for_all(comm_,
                  [&]
                  {
                    // The old summary goes first and the new one comes last: whenever the
                    // folder holds a summary.json, the files beside it are that run's.
                    const auto old_files = previous_results(dir_);
                    fs::remove(dir_ / "summary.json");
                    for (const auto& f : old_files)
                      if (fs::is_regular_file(fs::symlink_status(dir_ / f)))
                        fs::remove(dir_ / f);
                    const auto files = staged_files();
                    for (const auto& f : files)
                      if (f != "summary.json")
                        fs::rename(staging_ / f, dir_ / f);
                    if (fs::exists(staging_ / "summary.json"))
                      fs::rename(staging_ / "summary.json", dir_ / "summary.json");
                    fs::remove_all(staging_);
                  });
  committed_ = true;
}
} // namespace dembridge::app
