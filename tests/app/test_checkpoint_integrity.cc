// The checkpoint file's integrity (app/checkpoint/checkpoint.h, docs/checkpoint.md): damage to
// any dataset is refused naming it, and seeded random damage anywhere in the file is refused or
// (bytes nothing reads) changes nothing; a file without checksums is refused.
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

// ---- Integrity ----------------------------------------------------------------------------------
namespace
{
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
