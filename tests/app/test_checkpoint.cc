// The checkpoint file (app/checkpoint.h, docs/checkpoint.md): every field type survives a write
// and a read bit for bit (empty arrays, quaternions, strings with NULs inside are not allowed,
// long texts), the header is read back, a file of another format version, no HDF5 file or no
// checkpoint is refused with the reason, a case that differs is refused naming the entries,
// the write is atomic (only the final name after a write; a stale .tmp is replaced), and a
// missing field is named. Integrity: damage to any dataset is refused naming it, and seeded
// random damage anywhere in the file is refused or (bytes nothing reads) changes nothing.
// Beside it: a resumed run's rate and ETA (dem/core/progress.h), the history file a resume
// needs, and write errors that name the file and the system's reason (dem/core/output_file.h).
#include "app/checkpoint/checkpoint.h"
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
namespace fs = std::filesystem;

namespace
{
fs::path scratch(const std::string& name)
{
  const fs::path dir = fs::temp_directory_path() / "dembridge_test_checkpoint";
  fs::create_directories(dir);
  return dir / name;
}

struct Fields
{
  std::vector<double> d{1.0, -0.0, std::numeric_limits<double>::denorm_min(), 1e308,
                        std::numeric_limits<double>::infinity()};
  std::vector<std::int32_t> i32{-7, 0, 2147483647};
  std::vector<std::int64_t> i64{-(1LL << 62), 3};
  std::vector<std::uint8_t> u8{0, 255};
  std::vector<std::uint32_t> u32{4294967295u};
  std::vector<dem::Vec3> v3{{1, 2, 3}, {0.1, 0.2, 0.3}};
  std::vector<dem::Quat> q{dem::Quat(0.5, -0.5, 0.5, 0.5), dem::Quat::Identity()};
  std::vector<double> empty;
  std::string text = "line 1\nline 2, with = and \"quotes\"";
  std::string empty_text;
  double x = 0.1 + 0.2;
  long n = 1234567890123L;
  bool flag = true;

  void visit(dem::StateArchive& a)
  {
    dem::StateGroup g(a, "fields");
    a.io("d", d);
    a.io("i32", i32);
    a.io("i64", i64);
    a.io("u8", u8);
    a.io("u32", u32);
    a.io("v3", v3);
    a.io("q", q);
    a.io("empty", empty);
    {
      dem::StateGroup inner(a, "inner");
      a.io("text", text);
      a.io("empty_text", empty_text);
    }
    a.io("x", x);
    a.io("n", n);
    a.io("flag", flag);
  }
};

app::CheckpointHeader header()
{
  app::CheckpointHeader h;
  h.step = 42;
  h.time = 1.25e-3;
  h.version = "0.1.0";
  h.git_commit = "abc";
  h.written_at = "2026-01-01T00:00:00Z";
  h.case_name = "case.prm";
  h.case_text = "subsection Simulation\n  set end time = 0.01\nend\n";
  h.mpi_ranks = 3;
  return h;
}

/// Rewrites the root attribute format_version of @p file.
void set_format_version(const fs::path& file, std::int32_t version)
{
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t attr = H5Aopen(f, "format_version", H5P_DEFAULT);
  ASSERT_GE(attr, 0);
  EXPECT_GE(H5Awrite(attr, H5T_NATIVE_INT32, &version), 0);
  H5Aclose(attr);
  H5Fclose(f);
}

std::string error_of(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const dem::InputError& e)
  {
    return e.what();
  }
  return "(no error)";
}
} // namespace

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

// ---- Integrity ----------------------------------------------------------------------------------
namespace
{
/// A checkpoint shaped like a run's: groups of more entries than HDF5 keeps in an object header
/// (its dense link storage), arrays large and small, texts, empty arrays; seeded contents.
struct RunLike
{
  Fields fields;
  std::vector<dem::Vec3> position, velocity, force;
  std::vector<dem::Quat> orientation;
  std::vector<double> radius, mass, kn, ks, rest_length, energy;
  std::vector<std::int32_t> a, b;
  std::vector<std::uint8_t> state, model;
  std::string parameters;

  RunLike()
  {
    std::mt19937_64 random(2024);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int k = 0; k < 500; ++k)
    {
      position.emplace_back(u(random), u(random), u(random));
      velocity.emplace_back(u(random), u(random), u(random));
      force.emplace_back(u(random), u(random), u(random));
      orientation.push_back(dem::Quat(u(random), u(random), u(random), u(random)));
      radius.push_back(u(random)), mass.push_back(u(random));
    }
    for (int k = 0; k < 1500; ++k)
    {
      kn.push_back(u(random)), ks.push_back(u(random)), rest_length.push_back(u(random));
      a.push_back(std::int32_t(random() % 500)), b.push_back(std::int32_t(random() % 500));
      state.push_back(std::uint8_t(random() % 3)), model.push_back(std::uint8_t(random() % 3));
    }
    energy = {u(random), u(random), u(random)};
    for (int k = 0; k < 200; ++k)
      parameters += "  set entry " + std::to_string(k) + " = " + std::to_string(u(random)) + "\n";
  }

  void visit(dem::StateArchive& ar)
  {
    fields.visit(ar);
    {
      dem::StateGroup g(ar, "particles");
      ar.io("position", position), ar.io("velocity", velocity), ar.io("force", force);
      ar.io("orientation", orientation), ar.io("radius", radius), ar.io("mass", mass);
    }
    {
      dem::StateGroup g(ar, "bonds");
      ar.io("a", a), ar.io("b", b), ar.io("kn", kn), ar.io("ks", ks);
      ar.io("rest_length", rest_length), ar.io("state", state), ar.io("model", model);
      std::vector<double> none;
      ar.io("damage", none), ar.io("kappa_max", none), ar.io("dissipated", none);
      dem::StateGroup inner(ar, "energy");
      ar.io("terms", energy);
    }
    dem::StateGroup g(ar, "output");
    ar.io("parameters", parameters);
  }

  /// Every value, bit for bit.
  bool same(const RunLike& o) const
  {
    auto bits = [](const auto& x, const auto& y)
    {
      return x.size() == y.size() &&
             (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
    };
    const Fields &f = fields, &g = o.fields;
    return bits(f.d, g.d) && f.i32 == g.i32 && f.i64 == g.i64 && f.u8 == g.u8 && f.u32 == g.u32 &&
           f.v3 == g.v3 && bits(f.q, g.q) && f.empty == g.empty && f.text == g.text &&
           f.empty_text == g.empty_text && bits(std::vector{f.x}, std::vector{g.x}) && f.n == g.n &&
           f.flag == g.flag && bits(position, o.position) && bits(velocity, o.velocity) &&
           bits(force, o.force) && bits(orientation, o.orientation) && bits(radius, o.radius) &&
           bits(mass, o.mass) && a == o.a && b == o.b && bits(kn, o.kn) && bits(ks, o.ks) &&
           bits(rest_length, o.rest_length) && state == o.state && model == o.model &&
           bits(energy, o.energy) && parameters == o.parameters;
  }

  /// Emptied, so that a read must fill every field.
  void clear()
  {
    fields.d.clear(), fields.i32.clear(), fields.text.clear(), fields.x = 0, fields.n = 0;
    position.clear(), orientation.clear(), kn.clear(), state.clear(), parameters.clear();
    energy.clear();
  }
};

struct Extent
{
  haddr_t offset;
  hsize_t bytes;
  std::string path;
};

/// Where each dataset's data lie in @p file (contiguous layout; empty ones have none).
std::vector<Extent> dataset_extents(const fs::path& file)
{
  std::vector<Extent> out;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  auto visit = [](hid_t root, const char* name, const H5O_info_t* info, void* data) -> herr_t
  {
    if (info->type != H5O_TYPE_DATASET)
      return 0;
    const hid_t set = H5Dopen2(root, name, H5P_DEFAULT);
    const haddr_t offset = H5Dget_offset(set);
    if (offset != HADDR_UNDEF && H5Dget_storage_size(set) > 0)
      static_cast<std::vector<Extent>*>(data)->push_back(
          {offset, H5Dget_storage_size(set), "/" + std::string(name)});
    H5Dclose(set);
    return 0;
  };
  H5Ovisit(f, H5_INDEX_NAME, H5_ITER_INC, visit, &out);
  H5Fclose(f);
  return out;
}

/// @p file with @p bytes written over it at @p offset (cut at the end of the file).
void damage(const fs::path& file, std::uintmax_t offset, const std::vector<unsigned char>& bytes)
{
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(std::streamoff(offset));
  const std::uintmax_t n = std::min<std::uintmax_t>(bytes.size(), fs::file_size(file) - offset);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(n));
}

fs::path run_like_checkpoint(const std::string& name)
{
  const fs::path file = scratch(name);
  RunLike written;
  app::write_checkpoint(file, header(), [&](dem::StateArchive& a) { written.visit(a); });
  return file;
}
} // namespace

// One byte changed in the data of any dataset: refused, naming the file and that dataset, by the
// whole-file check a resume makes first and by the read itself.
TEST(CheckpointIntegrity, DamageToAnyDatasetIsRefusedNamingIt)
{
  const fs::path pristine = run_like_checkpoint("pristine.h5"), file = scratch("damaged.h5");
  const auto extents = dataset_extents(pristine);
  ASSERT_GE(extents.size(), 25u); // every non-empty dataset of RunLike and the header
  for (const auto& e : extents)
  {
    fs::copy_file(pristine, file, fs::copy_options::overwrite_existing);
    std::ifstream in(file, std::ios::binary);
    in.seekg(std::streamoff(e.offset + e.bytes / 2));
    const unsigned char old = static_cast<unsigned char>(in.get());
    in.close();
    damage(file, e.offset + e.bytes / 2, {static_cast<unsigned char>(old ^ 0x10)});
    const std::string expected = ": " + e.path + ": damaged: its data do not match their checksum";
    const std::string verified = error_of([&] { app::verify_checkpoint(file); });
    EXPECT_EQ(verified,
              file.string() + expected + "; the run cannot continue from this checkpoint");
    if (e.path.rfind("/header/", 0) == 0)
      continue; // read_checkpoint_header reads these (a resume verifies the whole file first)
    RunLike read;
    const std::string restored =
        error_of([&] { app::read_checkpoint(file, [&](dem::StateArchive& a) { read.visit(a); }); });
    EXPECT_NE(restored.find(expected), std::string::npos) << restored;
  }
}

// 256 seeded random bytes at 1 %, 2 %, ..., 99 % of the file: refused, naming the file (and the
// dataset when the damage lies in one's data), or, where nothing reads those bytes, read back
// exactly as written. Never a different state.
TEST(CheckpointIntegrity, RandomDamageIsRefusedOrChangesNothing)
{
  const fs::path pristine = run_like_checkpoint("pristine_random.h5");
  const fs::path file = scratch("random_damage.h5");
  const auto extents = dataset_extents(pristine);
  const std::uintmax_t size = fs::file_size(pristine);
  RunLike expected;
  std::mt19937 random(38);
  int refused = 0, harmless = 0, named = 0;
  for (int percent = 1; percent < 100; ++percent)
  {
    const std::uintmax_t offset = size * std::uintmax_t(percent) / 100;
    std::vector<unsigned char> bytes(256);
    for (auto& byte : bytes)
      byte = static_cast<unsigned char>(random());
    fs::copy_file(pristine, file, fs::copy_options::overwrite_existing);
    damage(file, offset, bytes);
    const std::uintmax_t end = std::min<std::uintmax_t>(offset + bytes.size(), size);
    std::string inside; // the dataset whose data hold the whole damaged range
    for (const auto& e : extents)
      if (offset >= e.offset && end <= e.offset + e.bytes)
        inside = e.path;
    const std::string what = error_of([&] { app::verify_checkpoint(file); });
    if (what != "(no error)")
    {
      ++refused;
      EXPECT_EQ(what.rfind(file.string() + ": ", 0), 0u) << percent << " %: " << what;
      if (std::getenv("DEMBRIDGE_TEST_VERBOSE"))
        std::cout << percent << " %: " << what << '\n';
      if (!inside.empty())
      {
        ++named;
        EXPECT_NE(what.find(": " + inside + ": damaged"), std::string::npos)
            << percent << " %: " << what;
      }
      continue;
    }
    ++harmless;
    EXPECT_TRUE(inside.empty()) << percent << " %: damage in " << inside << " not found";
    RunLike read;
    read.clear();
    app::read_checkpoint(file, [&](dem::StateArchive& a) { read.visit(a); });
    EXPECT_TRUE(read.same(expected)) << percent << " %: accepted, and read back different";
  }
  std::cout << "random damage at 99 offsets of a " << size << "-byte checkpoint: " << refused
            << " refused (" << named << " inside one dataset's data, named), " << harmless
            << " in bytes nothing reads\n";
  EXPECT_GT(named, 50);
}

// A checkpoint of an older format (no checksums) is refused by its version, with the reason.
TEST(CheckpointIntegrity, AFileWithoutChecksumsIsRefused)
{
  const fs::path file = run_like_checkpoint("no_checksum.h5");
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t set = H5Dopen2(f, "particles/radius", H5P_DEFAULT);
  EXPECT_GE(H5Adelete(set, "crc32"), 0);
  H5Dclose(set);
  H5Fclose(f);
  EXPECT_EQ(error_of([&] { app::verify_checkpoint(file); }),
            file.string() + ": /particles/radius: damaged: no checksum (attribute 'crc32'); the "
                            "run cannot continue from this checkpoint");
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
