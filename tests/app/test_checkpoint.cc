// The checkpoint file (app/checkpoint/checkpoint.h, docs/checkpoint.md): every field type survives
// a write and a read bit for bit (empty arrays, quaternions, strings with NULs inside are not
// allowed, long texts), the header is read back, a file of another format version, no HDF5 file or
// no checkpoint is refused with the reason, a case that differs is refused naming the entries, the
// write is atomic (only the final name after a write; a stale .tmp is replaced), and a missing
// field is named. Its integrity: test_checkpoint_integrity.cc. Beside it: a resumed run's rate and
// ETA (dem/core/progress.h), the history file a resume needs, and write errors that name the file
// and the system's reason (dem/core/output_file.h).
#include "app/checkpoint/checkpoint.h"
#include "checkpoint_test_fields.h"
#include "dem/core/byte_archive.h"
#include "dem/core/history_file.h"
#include "dem/core/output_file.h"
#include "dem/core/progress.h"
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <limits>
#include <random>

using namespace dembridge;
using namespace checkpoint_test;
namespace fs = std::filesystem;

TEST(Checkpoint, EveryFieldTypeRoundTripsBitForBit)
{
  const fs::path file = scratch("round_trip.h5");
  Fields written;
  app::write_checkpoint(file, header(), [&](dem::StateArchive& a) { written.visit(a); });
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));

  Fields read;
  read.d.clear(), read.i32 = {1}, read.i64.clear(), read.u8.clear(), read.u32.clear();
  read.v3.clear(), read.q.clear(), read.empty = {5.0}, read.text.clear(), read.empty_text = "x";
  read.x = 0, read.n = 0, read.flag = false;
  app::read_checkpoint(file, [&](dem::StateArchive& a) { read.visit(a); });
  ASSERT_EQ(read.d.size(), written.d.size());
  for (std::size_t k = 0; k < read.d.size(); ++k)
    EXPECT_EQ(std::memcmp(&read.d[k], &written.d[k], sizeof(double)), 0) << k; // -0.0 too
  EXPECT_EQ(read.i32, written.i32);
  EXPECT_EQ(read.i64, written.i64);
  EXPECT_EQ(read.u8, written.u8);
  EXPECT_EQ(read.u32, written.u32);
  EXPECT_EQ(read.v3, written.v3);
  ASSERT_EQ(read.q.size(), written.q.size());
  for (std::size_t k = 0; k < read.q.size(); ++k)
    EXPECT_EQ(read.q[k].coeffs(), written.q[k].coeffs());
  EXPECT_TRUE(read.empty.empty());
  EXPECT_EQ(read.text, written.text);
  EXPECT_EQ(read.empty_text, "");
  EXPECT_EQ(read.x, written.x);
  EXPECT_EQ(read.n, written.n);
  EXPECT_EQ(read.flag, true);

  const app::CheckpointHeader h = app::read_checkpoint_header(file);
  EXPECT_EQ(h.step, 42);
  EXPECT_EQ(h.time, 1.25e-3);
  EXPECT_EQ(h.case_text, header().case_text);
  EXPECT_EQ(h.case_name, "case.prm");
  EXPECT_EQ(h.mpi_ranks, 3);
}

// A header without mpi_ranks (written before coupled runs were checkpointed on several ranks)
// is one rank's.
TEST(Checkpoint, HeaderWithoutRanksIsOneRanks)
{
  const fs::path file = scratch("no_ranks.h5");
  app::write_checkpoint(file, header(), [](dem::StateArchive&) {});
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_GE(H5Ldelete(f, "header/mpi_ranks", H5P_DEFAULT), 0);
  H5Fclose(f);
  EXPECT_EQ(app::read_checkpoint_header(file).mpi_ranks, 1);
}

// The in-memory archive that hands rank 0's restored state to the other ranks: every field
// type bit for bit, in the order named; another name is a program error.
TEST(Checkpoint, ByteArchiveRoundTripsBitForBit)
{
  Fields written;
  dem::ByteArchive packed;
  written.visit(packed);
  Fields read;
  read.d.clear(), read.i32 = {1}, read.v3.clear(), read.q.clear(), read.empty = {5.0};
  read.text.clear(), read.empty_text = "x", read.x = 0, read.n = 0, read.flag = false;
  dem::ByteArchive unpacked(packed.bytes());
  read.visit(unpacked);
  ASSERT_EQ(read.d.size(), written.d.size());
  EXPECT_EQ(std::memcmp(read.d.data(), written.d.data(), read.d.size() * sizeof(double)), 0);
  EXPECT_EQ(read.i32, written.i32);
  EXPECT_EQ(read.i64, written.i64);
  EXPECT_EQ(read.u32, written.u32);
  EXPECT_EQ(read.v3, written.v3);
  ASSERT_EQ(read.q.size(), written.q.size());
  EXPECT_EQ(read.q[0].coeffs(), written.q[0].coeffs());
  EXPECT_TRUE(read.empty.empty());
  EXPECT_EQ(read.text, written.text);
  EXPECT_EQ(read.empty_text, "");
  EXPECT_EQ(read.x, written.x);
  EXPECT_EQ(read.n, written.n);
  EXPECT_TRUE(read.flag);
  dem::ByteArchive other(packed.bytes());
  std::vector<double> v;
  dem::StateGroup g(other, "fields");
  EXPECT_THROW(other.io("velocity", v), std::logic_error);
}

TEST(Checkpoint, QuaternionsAreStoredWFirst)
{
  const fs::path file = scratch("quaternion.h5");
  std::vector<dem::Quat> q{dem::Quat(0.1, 0.2, 0.3, 0.4)}; // w, x, y, z
  app::write_checkpoint(file, header(), [&](dem::StateArchive& a) { a.io("q", q); });
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t set = H5Dopen2(f, "q", H5P_DEFAULT);
  double row[4] = {};
  ASSERT_GE(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, row), 0);
  H5Dclose(set);
  H5Fclose(f);
  EXPECT_EQ(row[0], 0.1);
  EXPECT_EQ(row[1], 0.2);
  EXPECT_EQ(row[3], 0.4);
}

TEST(Checkpoint, OtherFormatVersionIsRefused)
{
  const fs::path file = scratch("version.h5");
  Fields f;
  app::write_checkpoint(file, header(), [&](dem::StateArchive& a) { f.visit(a); });
  for (const int other : {app::checkpoint_format_version - 1, app::checkpoint_format_version + 1})
  {
    set_format_version(file, other);
    const std::string what = error_of([&] { app::read_checkpoint_header(file); });
    EXPECT_NE(what.find("checkpoint format version " + std::to_string(other) +
                        ", this dembridge reads version " +
                        std::to_string(app::checkpoint_format_version) + " only"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.rfind(file.string(), 0), 0u) << what;
  }
}

TEST(Checkpoint, NotACheckpointIsRefused)
{
  const fs::path text = scratch("not_hdf5.h5");
  std::ofstream(text) << "hello\n";
  EXPECT_NE(error_of([&] { app::read_checkpoint_header(text); }).find("not an HDF5 file"),
            std::string::npos);
  const fs::path none = scratch("does_not_exist.h5");
  fs::remove(none);
  EXPECT_NE(error_of([&] { app::read_checkpoint_header(none); }).find("no checkpoint there"),
            std::string::npos);
  // an HDF5 file of something else
  const fs::path other = scratch("other.h5");
  H5Fclose(H5Fcreate(other.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  EXPECT_NE(error_of([&] { app::read_checkpoint_header(other); })
                .find("not a dembridge checkpoint (no 'format' attribute)"),
            std::string::npos);
}

TEST(Checkpoint, AnotherCaseIsRefusedNamingTheEntries)
{
  const app::CheckpointHeader h = header();
  EXPECT_NO_THROW(app::check_same_case(h, h.case_text, "cp.h5"));
  const std::string what = error_of(
      [&]
      {
        app::check_same_case(
            h, "subsection Simulation\n  set end time = 0.02\nend\nset Mode = dem\n", "cp.h5");
      });
  EXPECT_EQ(what, "cp.h5: the checkpoint is of another case (case.prm): Simulation/end time is "
                  "'0.01' there, '0.02' here; Mode is '(no such entry)' there, 'dem' here");
}

TEST(Checkpoint, MissingFieldIsNamed)
{
  const fs::path file = scratch("missing.h5");
  app::write_checkpoint(file, header(), [](dem::StateArchive&) {});
  std::vector<double> v;
  const std::string what = error_of(
      [&]
      {
        app::read_checkpoint(file,
                             [&](dem::StateArchive& a)
                             {
                               dem::StateGroup g(a, "header");
                               a.io("velocity", v);
                             });
      });
  EXPECT_EQ(what, "missing.h5: /header/velocity: missing from the checkpoint (a file of another "
                  "format?)");
}

TEST(Checkpoint, WriteReplacesAStaleTemporaryAndTheOldFile)
{
  const fs::path file = scratch("atomic.h5");
  std::ofstream(file.string() + ".tmp") << "half a checkpoint of a killed run";
  Fields f;
  f.n = 1;
  app::write_checkpoint(file, header(), [&](dem::StateArchive& a) { f.visit(a); });
  f.n = 2;
  app::write_checkpoint(file, header(), [&](dem::StateArchive& a) { f.visit(a); });
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  Fields read;
  app::read_checkpoint(file, [&](dem::StateArchive& a) { read.visit(a); });
  EXPECT_EQ(read.n, 2);
}

TEST(Checkpoint, SizedArraysMustMatchTheModel)
{
  const fs::path file = scratch("sized.h5");
  std::vector<double> three{1, 2, 3};
  app::write_checkpoint(file, header(), [&](dem::StateArchive& a) { a.io("radius", three); });
  std::vector<double> two(2);
  const std::string what = error_of(
      [&]
      { app::read_checkpoint(file, [&](dem::StateArchive& a) { a.io_sized("radius", two); }); });
  EXPECT_EQ(what, "sized.h5: /radius: 3 entries in the checkpoint, 2 in this model");
}

// ---- A resumed run's rate and ETA, the history file a resume needs ------------------------------
// Resumed at step 8000 and 4 s later at step 10000 of 20000: 500 steps/s and 20 s left (counting
// the checkpoint's steps would give 2500 steps/s and 4 s).
TEST(ResumedRun, RateAndEtaCountTheStepsSinceTheResume)
{
  const auto resumed = dem::StepRate::clock::time_point{} + std::chrono::seconds(100);
  const dem::StepRate rate(8000, resumed);
  const auto now = resumed + std::chrono::seconds(4);
  EXPECT_EQ(rate.steps_made(10000), 2000);
  EXPECT_DOUBLE_EQ(rate.per_second(10000, now), 500.0);
  EXPECT_DOUBLE_EQ(rate.seconds_left(10000, 20000, now), 20.0);
  EXPECT_EQ(rate.per_second(8000, resumed), 0.0); // no step, no time: no rate, no ETA
  EXPECT_EQ(rate.seconds_left(8000, 20000, resumed), 0.0);
  const dem::StepRate fresh(0, resumed);
  EXPECT_DOUBLE_EQ(fresh.per_second(10000, now), 2500.0);
}

TEST(ResumedRun, AMissingHistoryFileIsNamedByItsFullPath)
{
  const fs::path missing = scratch(".partial_missing") / "history.csv.part";
  fs::remove_all(missing.parent_path());
  dem::HistoryFile history;
  const std::string what = error_of([&] { history.open(missing, true); });
  EXPECT_EQ(what, missing.string() + ": missing: the checkpoint continues this file of the "
                                     "interrupted run; cannot resume without it");
  EXPECT_FALSE(fs::exists(missing)); // not created empty
}

// ---- Write errors name the file and the system's reason -----------------------------------------
// /dev/full refuses every write with ENOSPC, as a full disk does (no mount needed, root or not).
TEST(WriteErrors, AFullDiskIsNamed)
{
  ASSERT_TRUE(fs::exists("/dev/full"));
  const std::string full = "/dev/full: cannot write: No space left on device";
  auto message = [](const std::function<void()>& f)
  {
    try
    {
      f();
    }
    catch (const std::runtime_error& e)
    {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  // a large write fails in the insertion, a small one when it is closed
  EXPECT_EQ(message([] { dem::OutputFile("/dev/full") << std::string(1 << 20, 'x'); }), full);
  EXPECT_EQ(message(
                []
                {
                  dem::OutputFile out("/dev/full");
                  out << "a short line\n";
                  out.close();
                }),
            full);
  // the history file's rows and the checkpoint's flush, through a name on a full disk
  EXPECT_EQ(message(
                []
                {
                  dem::HistoryFile history;
                  history.open("/dev/full", false);
                  history.stream() << "step,time\n";
                  history.close();
                }),
            full);
  const fs::path file = scratch("full.h5"), tmp = file.string() + ".tmp";
  fs::remove(tmp);
  fs::create_symlink("/dev/full", tmp);
  const std::string checkpoint = message(
      [&]
      {
        RunLike state;
        app::write_checkpoint(file, header(), [&](dem::StateArchive& a) { state.visit(a); });
      });
  fs::remove(tmp);
  EXPECT_EQ(checkpoint.rfind(tmp.string() + ": ", 0), 0u) << checkpoint;
  EXPECT_NE(checkpoint.find("(No space left on device)"), std::string::npos) << checkpoint;
}
