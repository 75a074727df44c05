#include "output_folder.h"
#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <stdexcept>

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
} // namespace

OutputFolder::OutputFolder(const fs::path& dir, MPI_Comm comm, bool resume)
    : dir_(fs::absolute(dir).lexically_normal()), staging_(dir_ / ".partial"), comm_(comm),
      writer_(is_rank0(comm))
{
  if (writer_)
  {
    if (fs::exists(dir_) && !fs::is_directory(dir_))
      throw std::runtime_error(dir_.string() + ": the output folder is a file");
    fs::create_directories(dir_);
    if (!resume)
      fs::remove_all(staging_); // left by a killed run
    fs::create_directories(staging_);
  }
  MPI_Barrier(comm_);
}

OutputFolder::~OutputFolder()
{
  if (writer_ && !committed_)
  {
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
  }
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
  for (const char* name :
       {"summary.json", "summary.json.part", "parameters.prm", "history.csv", "history.csv.part",
        "particle_stress.csv", "particle_stress.csv.part", "cracks.csv", "comparison.csv",
        "comparison.png"})
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
  if (writer_)
  {
    // The old summary goes first and the new one comes last: whenever the folder holds a
    // summary.json, the files beside it are that run's.
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
  }
  committed_ = true;
  MPI_Barrier(comm_);
}
} // namespace dembridge::app
