#include "app/checkpoint/checkpoint.h"
#include "app/checkpoint/hdf5_archive.h"
#include "app/input/case_scan.h"
#include "app/job/provenance.h"
#include "app/job/version.h"
#include "dem/core/fsync_path.h"
#include <array>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <deal.II/base/mpi.h>
#include <hdf5.h>
#include <map>
#include <sstream>

namespace dembridge::app
{
namespace fs = std::filesystem;
using dem::InputError;

namespace
{
using hdf5::Handle;
using hdf5::Hdf5Archive;
using hdf5::quiet_hdf5;

/// @p with_ranks: mpi_ranks is there (files before it had one-rank runs only)
void visit_header(dem::StateArchive& a, CheckpointHeader& h, bool with_ranks)
{
  dem::StateGroup group(a, "header");
  a.io("step", h.step);
  a.io("time", h.time);
  if (with_ranks)
    a.io("mpi_ranks", h.mpi_ranks);
  a.io("dembridge_version", h.version);
  a.io("git_commit", h.git_commit);
  a.io("written_at", h.written_at);
  a.io("case", h.case_name);
  a.io("parameters", h.case_text);
}

void write_string_attribute(hid_t at, const char* name, const std::string& value)
{
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.size());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(at, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.ok() || H5Awrite(attr.get(), type.get(), value.data()) < 0)
    throw std::runtime_error(std::string("checkpoint: cannot write the attribute ") + name +
                             hdf5::with_reason(hdf5::hdf5_reason()));
}

/// "FILE: WHAT: damaged..." (InputError): a checkpoint whose bytes are not those written.
[[noreturn]] void damaged(const std::string& file, const std::string& what, const std::string& why)
{
  throw InputError(file + ": " + what + "damaged: " + why +
                   "; the run cannot continue from this checkpoint");
}

/// Root attributes "format" and "format_version"; InputError when absent or another.
void check_format(hid_t file, const std::string& name)
{
  const htri_t has_format = H5Aexists(file, "format"),
               has_version = H5Aexists(file, "format_version");
  if (has_format < 0 || has_version < 0)
    damaged(name,
            "/: ", "HDF5 cannot read its attributes" + hdf5::with_reason(hdf5::hdf5_reason()));
  if (!has_format || !has_version)
    throw InputError(name + ": not a dembridge checkpoint (no 'format' attribute)");
  {
    Handle attr(H5Aopen(file, "format", H5P_DEFAULT), H5Aclose);
    Handle type(H5Aget_type(attr.get()), H5Tclose);
    std::string value(H5Tget_class(type.get()) == H5T_STRING ? H5Tget_size(type.get()) : 0, '\0');
    Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(memory.get(), std::max<std::size_t>(1, value.size()));
    if (value.empty() || H5Aread(attr.get(), memory.get(), value.data()) < 0)
      throw InputError(name + ": not a dembridge checkpoint (unreadable 'format')");
    value.erase(value.find_last_not_of('\0') + 1);
    if (value != checkpoint_format_name)
      throw InputError(name + ": not a dembridge checkpoint (format '" + value + "')");
  }
  Handle attr(H5Aopen(file, "format_version", H5P_DEFAULT), H5Aclose);
  std::int32_t version = -1;
  if (H5Aread(attr.get(), H5T_NATIVE_INT32, &version) < 0)
    throw InputError(name + ": unreadable 'format_version'");
  if (version != checkpoint_format_version)
    throw InputError(name + ": checkpoint format version " + std::to_string(version) +
                     ", this dembridge reads version " + std::to_string(checkpoint_format_version) +
                     " only");
  // why: superblock version 2 and later is HDF5's format 1.8, whose metadata carries checksums
  H5F_info2_t info{};
  if (H5Fget_info2(file, &info) < 0 || info.super.version < 2)
    damaged(name, "",
            "its HDF5 superblock is of version " + std::to_string(info.super.version) +
                ", which has no checksums (not as dembridge writes it)");
}

Handle open_checkpoint(const fs::path& file)
{
  quiet_hdf5();
  const std::string name = file.string();
  if (!fs::is_regular_file(file))
    throw InputError(name + ": no checkpoint there (Output/checkpoint interval writes one)");
  if (H5Fis_hdf5(name.c_str()) <= 0)
    throw InputError(name + ": not an HDF5 file");
  Handle h(H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!h.ok())
    damaged(name, "", "HDF5 cannot open it" + hdf5::with_reason(hdf5::hdf5_reason()));
  check_format(h.get(), name);
  return h;
}

/// Reads every dataset under @p group (at @p path, "/" for the root) and compares its bytes with
/// its checksum; InputError naming the file and the dataset, or the group HDF5 could not read.
void verify_group(hid_t group, const std::string& path, const std::string& name,
                  std::uintmax_t file_bytes)
{
  std::vector<std::string> links;
  auto collect = [](hid_t, const char* link, const H5L_info_t* info, void* out) -> herr_t
  {
    if (info->type != H5L_TYPE_HARD)
      return -1; // dembridge writes hard links only
    static_cast<std::vector<std::string>*>(out)->push_back(link);
    return 0;
  };
  if (H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &links) < 0)
    damaged(name, path + ": ", "HDF5 cannot list it" + hdf5::with_reason(hdf5::hdf5_reason()));
  for (const std::string& link : links)
  {
    const std::string at = path + link;
    Handle object(H5Oopen(group, link.c_str(), H5P_DEFAULT), H5Oclose);
    if (!object.ok())
      damaged(name, at + ": ", "HDF5 cannot open it" + hdf5::with_reason(hdf5::hdf5_reason()));
    const H5I_type_t kind = H5Iget_type(object.get());
    if (kind == H5I_GROUP)
    {
      verify_group(object.get(), at + "/", name, file_bytes);
      continue;
    }
    if (kind != H5I_DATASET)
      damaged(name, at + ": ", "neither a group nor a dataset");
    Handle type(H5Dget_type(object.get()), H5Tclose);
    Handle space(H5Dget_space(object.get()), H5Sclose);
    const hssize_t count = space.ok() ? H5Sget_simple_extent_npoints(space.get()) : -1;
    const std::size_t element = type.ok() ? H5Tget_size(type.get()) : 0;
    // why: a size no file of this length can hold is damage, not an allocation to attempt
    if (count < 0 || element == 0 || std::uintmax_t(count) > file_bytes / element)
      damaged(name, at + ": ",
              "HDF5 cannot read its type or size" + hdf5::with_reason(hdf5::hdf5_reason()));
    // the bytes as they lie in the file: read in the file's own type, no conversion
    std::vector<unsigned char> bytes(std::size_t(count) * element);
    if (!bytes.empty() &&
        H5Dread(object.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0)
      damaged(name, at + ": ", "HDF5 cannot read it" + hdf5::with_reason(hdf5::hdf5_reason()));
    const std::string mismatch =
        hdf5::checksum_mismatch(object.get(), hdf5::crc32_of(bytes.data(), bytes.size()));
    if (!mismatch.empty())
      damaged(name, at + ": ", mismatch);
  }
}

} // namespace

std::string checkpoint_case_text(const dealii::ParameterHandler& prm, const fs::path& case_dir)
{
  // what may change between the interrupted run and its resume: how often checkpoints are
  // written and the thread count (the results do not depend on it)
  auto may_change = [](const PrmLine& l)
  {
    return l.kind == PrmLine::Kind::set && l.path.size() == 1 &&
           ((l.path[0] == "Output" &&
             (l.key == "checkpoint interval" || l.key == "checkpoint wall interval")) ||
            (l.path[0] == "Simulation" && l.key == "threads"));
  };
  return rewrite_prm_lines(parameters_file_text(prm, case_dir, ""),
                           [&](const PrmLine& l) -> std::optional<std::string>
                           {
                             if (may_change(l))
                               return std::nullopt;
                             return l.text;
                           });
}

namespace
{
/// The interrupted run's history file, which a resume continues from the length the checkpoint
/// recorded: DIR/.partial (output_folder.h's staging folder) holds it as history.csv.part (DEM
/// and coupled runs, /output/history_bytes) or history.csv (FE dynamics, /fem_run/). Refused
/// here, naming the file, rather than in the run, where a failure clears the staging folder.
void check_staged_history(const fs::path& file)
{
  Handle h = open_checkpoint(file);
  for (const auto& [group, staged] :
       {std::pair{"output", "history.csv.part"}, std::pair{"fem_run", "history.csv"}})
  {
    if (H5Lexists(h.get(), group, H5P_DEFAULT) <= 0 ||
        H5Lexists(h.get(), (std::string(group) + "/history_bytes").c_str(), H5P_DEFAULT) <= 0)
      continue;
    Hdf5Archive hdf5(h.get(), true, file.string());
    dem::StateArchive& archive = hdf5;
    long bytes = 0;
    {
      dem::StateGroup g(archive, group);
      archive.io("history_bytes", bytes);
    }
    const fs::path history = file.parent_path() / ".partial" / staged;
    std::error_code missing;
    const std::uintmax_t size = fs::file_size(history, missing);
    if (missing || size < std::uintmax_t(std::max(0L, bytes)))
      throw InputError(history.string() + ": " +
                       (missing ? std::string("missing") : std::to_string(size) + " bytes") +
                       ", but the checkpoint was written after " + std::to_string(bytes) +
                       " bytes of it: cannot resume without the run's own file");
    return;
  }
}

/// Whether a DEM checkpoint was written by the run on several ranks (distributed/): its contacts
/// are held by global ids (solver/contribution_0/ranks), not in the one-rank layout. Such a run
/// on one rank (resumed from several) writes them so too.
bool holds_contacts_of_ranks(const fs::path& file)
{
  Handle h = open_checkpoint(file);
  for (const char* group : {"solver", "solver/contribution_0", "solver/contribution_0/ranks"})
    if (H5Lexists(h.get(), group, H5P_DEFAULT) <= 0)
      return false;
  return true;
}

/// A fresh run refuses a folder that holds a checkpoint; a resumed one reads the checkpoint's
/// header and refuses another format, case or number of MPI ranks (@p s.resumed_step, time);
/// @p any_ranks: a checkpoint written on several ranks resumes on any number (a DEM run's).
void check_checkpoint_file(CheckpointSettings& s, const std::string& output_dir, bool any_ranks)
{
  if (!s.resume)
  {
    if (fs::exists(s.file))
    {
      std::string at;
      try
      {
        const CheckpointHeader h = read_checkpoint_header(s.file);
        at = " (step " + std::to_string(h.step) + ", t = " + std::to_string(h.time) + " s)";
      }
      catch (const std::exception&)
      {
      }
      throw InputError(s.file.string() + ": the folder holds the checkpoint of an interrupted " +
                       "run" + at + "; continue it with --resume " + output_dir +
                       ", or delete the file to start afresh");
    }
    return;
  }
  verify_checkpoint(s.file); // every byte it holds, before anything is built or staged
  const CheckpointHeader h = read_checkpoint_header(s.file);
  check_same_case(h, s.case_text, s.file);
  // why: each rank sums its share of the continuum's works; bit-for-bit needs the same split.
  // A DEM run on several ranks writes the whole run; on one its contacts in one store's layout,
  // which a DEM run on several ranks reads as such.
  const bool of_ranks = any_ranks && (h.mpi_ranks > 1 || holds_contacts_of_ranks(s.file));
  s.one_rank_contacts = any_ranks && !of_ranks && s.ranks > 1;
  s.whole_run = of_ranks || s.one_rank_contacts;
  if (h.mpi_ranks != s.ranks && !s.whole_run)
    throw InputError(s.file.string() + ": the checkpoint was written by a run on " +
                     std::to_string(h.mpi_ranks) + " MPI rank(s), this run has " +
                     std::to_string(s.ranks) + " (resume it with mpirun -np " +
                     std::to_string(h.mpi_ranks) + ")");
  check_staged_history(s.file);
  s.resumed_step = h.step;
  s.resumed_time = h.time;
}
} // namespace

CheckpointSettings prepare_checkpoint(const dealii::ParameterHandler& prm,
                                      const std::string& case_file, std::string& output_dir,
                                      const std::string& resume_dir)
{
  CheckpointSettings s;
  s.case_name = fs::path(case_file).filename().string();
  s.resume = !resume_dir.empty();
  if (s.resume)
  {
    if (!output_dir.empty() && fs::weakly_canonical(output_dir) != fs::weakly_canonical(resume_dir))
      throw InputError("--resume: the run continues in its own folder " + resume_dir +
                       " (drop --output-dir " + output_dir + ")");
    output_dir = resume_dir;
  }
  else if (output_dir.empty())
    output_dir = (fs::path("output") / fs::path(case_file).stem()).string();
  const std::string mode = prm.get("Mode");
  const bool asked = prm.get_double({"Output"}, "checkpoint interval") > 0 ||
                     prm.get_double({"Output"}, "checkpoint wall interval") > 0;
  const char* key = prm.get_double({"Output"}, "checkpoint interval") > 0
                        ? "Output/checkpoint interval"
                        : "Output/checkpoint wall interval";
  if (mode == "fem" && prm.get({"FEM"}, "problem") == "static" && (s.resume || asked))
    // why: one solve, no steps; refused rather than run without the checkpoints asked for
    throw InputError(s.case_name + ": " + (s.resume ? "--resume" : key) +
                     ": a static FE run (FEM/problem = static) has no time steps to checkpoint "
                     "(FE dynamics, DEM and coupled runs are checkpointed)");
  // why: a continuum (coupled or FE run) and a DEM run's particles are split over the ranks
  const bool mpi = dealii::Utilities::MPI::job_supports_mpi();
  const bool root = !mpi || dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  if (mpi)
    s.ranks = int(dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD));
  s.file = fs::absolute(fs::path(output_dir) / "checkpoint.h5").lexically_normal();
  s.case_text = checkpoint_case_text(prm, fs::absolute(case_file).parent_path());
  // rank 0 looks at the file, every rank gets its verdict (one line each, no rank left waiting)
  std::string refused;
  if (root)
    try
    {
      check_checkpoint_file(s, output_dir, mode == "dem");
    }
    catch (const std::exception& e)
    {
      refused = *e.what() ? e.what() : "checkpoint: unknown error";
    }
  if (mpi && dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
  {
    refused = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, refused, 0);
    s.resumed_step = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, s.resumed_step, 0);
    s.resumed_time = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, s.resumed_time, 0);
    s.whole_run = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, s.whole_run, 0);
    s.one_rank_contacts = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, s.one_rank_contacts, 0);
  }
  if (!refused.empty())
    throw InputError(refused);
  return s;
}

void finish_checkpoints(const CheckpointSettings& s)
{
  if (s.file.empty())
    return;
  std::error_code ignored;
  fs::remove(s.file, ignored);
  fs::remove(s.file.string() + ".tmp", ignored);
}

CheckpointHeader read_checkpoint_header(const fs::path& file)
{
  Handle h = open_checkpoint(file);
  Hdf5Archive archive(h.get(), true, file.filename().string());
  CheckpointHeader header;
  const bool with_ranks = H5Lexists(h.get(), "header", H5P_DEFAULT) > 0 &&
                          H5Lexists(h.get(), "header/mpi_ranks", H5P_DEFAULT) > 0;
  visit_header(archive, header, with_ranks);
  return header;
}

void verify_checkpoint(const fs::path& file)
{
  Handle h = open_checkpoint(file);
  verify_group(h.get(), "/", file.string(), fs::file_size(file));
}

void check_same_case(const CheckpointHeader& header, const std::string& case_text,
                     const fs::path& file)
{
  if (header.case_text == case_text)
    return;
  const auto there = prm_entries(header.case_text), here = prm_entries(case_text);
  std::string what;
  int listed = 0;
  auto add = [&](const std::string& key, const std::string& a, const std::string& b)
  {
    if (listed++ < 3)
      what +=
          std::string(what.empty() ? "" : "; ") + key + " is '" + a + "' there, '" + b + "' here";
  };
  for (const auto& [key, value] : there)
  {
    const auto it = here.find(key);
    if (it == here.end())
      add(key, value, "(no such entry)");
    else if (it->second != value)
      add(key, value, it->second);
  }
  for (const auto& [key, value] : here)
    if (!there.count(key))
      add(key, "(no such entry)", value);
  if (what.empty())
    what = "the parameter files differ in their comments or order";
  throw InputError(file.string() + ": the checkpoint is of another case (" + header.case_name +
                   "): " + what);
}

void write_checkpoint(const fs::path& file, const CheckpointHeader& header,
                      const std::function<void(dem::StateArchive&)>& visit)
{
  quiet_hdf5();
  static int written = 0;
  static const int kill_at = []
  {
    const char* v = std::getenv("DEMBRIDGE_TEST_KILL_IN_CHECKPOINT");
    return v ? std::atoi(v) : 0;
  }();
  ++written;
  const fs::path tmp = file.string() + ".tmp";
  {
    // HDF5's file format 1.8 (and no older): its metadata carries checksums (hdf5_archive.h)
    Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_V18);
    Handle creation(hdf5::compact_links(H5Pcreate(H5P_FILE_CREATE)), H5Pclose);
    Handle h(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, creation.get(), access.get()), H5Fclose);
    if (!h.ok())
      throw std::runtime_error(tmp.string() + ": cannot create the checkpoint" +
                               hdf5::with_reason(hdf5::hdf5_reason()));
    write_string_attribute(h.get(), "format", checkpoint_format_name);
    {
      Handle space(H5Screate(H5S_SCALAR), H5Sclose);
      Handle attr(H5Acreate2(h.get(), "format_version", H5T_STD_I32LE, space.get(), H5P_DEFAULT,
                             H5P_DEFAULT),
                  H5Aclose);
      const std::int32_t version = checkpoint_format_version;
      if (!attr.ok() || H5Awrite(attr.get(), H5T_NATIVE_INT32, &version) < 0)
        throw std::runtime_error(tmp.string() + ": cannot write the format version" +
                                 hdf5::with_reason(hdf5::hdf5_reason()));
    }
    Hdf5Archive archive(h.get(), false, tmp.string()); // write errors name the file
    CheckpointHeader copy = header;
    visit_header(archive, copy, true);
    if (written == kill_at)
    {
      H5Fflush(h.get(), H5F_SCOPE_GLOBAL); // half a checkpoint on the disk, then kill -9
      std::raise(SIGKILL);
    }
    visit(archive);
    if (H5Fflush(h.get(), H5F_SCOPE_GLOBAL) < 0 || H5Fclose(h.release()) < 0)
      throw std::runtime_error(tmp.string() + ": cannot write the checkpoint" +
                               hdf5::with_reason(hdf5::hdf5_reason()));
  }
  dem::fsync_path(tmp); // the data is on the disk before the name points at it
  fs::rename(tmp, file);
  dem::fsync_path(file.parent_path());
}

void read_checkpoint(const fs::path& file, const std::function<void(dem::StateArchive&)>& visit)
{
  Handle h = open_checkpoint(file);
  Hdf5Archive archive(h.get(), true, file.filename().string());
  visit(archive);
}

void visit_file_list(dem::StateArchive& a, const std::string& name,
                     std::vector<std::pair<double, std::string>>& files)
{
  std::vector<double> times;
  std::string names;
  for (const auto& [t, f] : files)
    times.push_back(t), names += f + "\n";
  a.io(name + "_times", times);
  a.io(name + "_files", names);
  if (!a.loading())
    return;
  files.clear();
  std::istringstream in(names);
  std::string f;
  for (double t : times)
  {
    if (!std::getline(in, f))
      throw InputError(a.where() + name + "_files: fewer names than times");
    files.emplace_back(t, f);
  }
}
CheckpointHeader make_checkpoint_header(const CheckpointSettings& settings, long step, double time)
{
  CheckpointHeader h;
  h.step = step;
  h.time = time;
  h.version = version();
  h.git_commit = git_commit();
  h.written_at = utc_now();
  h.case_name = settings.case_name;
  h.case_text = settings.case_text;
  h.mpi_ranks = settings.ranks;
  return h;
}
} // namespace dembridge::app
