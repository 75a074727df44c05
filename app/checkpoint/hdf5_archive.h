#pragma once
// The checkpoint's HDF5 side (docs/checkpoint.md): a scoped HDF5 handle, the checksums and
// dem::StateArchive on an open HDF5 file. Included by checkpoint.cc only (HDF5's C API stays out
// of the rest of the app).
//
// Integrity: every dataset carries the CRC-32 (zlib's) of its bytes as they lie in the file in an
// attribute `crc32`, checked whenever it is read; the structure around them (superblock, object
// headers with their attributes, group indexes) is HDF5's file format 1.8, whose metadata HDF5
// itself checksums and refuses when damaged. So no byte a resume reads is taken unchecked.
#include "dem/core/state_archive.h"
#include <bit>
#include <hdf5.h>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include <zlib.h>

namespace dembridge::app::hdf5
{
using dem::InputError;

static_assert(sizeof(dem::Vec3) == 3 * sizeof(double), "Vec3 rows are written as they lie");

/// Closes an HDF5 handle when it goes out of scope.
class Handle
{
public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  ~Handle()
  {
    if (id_ >= 0)
      close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }
  /// The handle, no longer closed here (the caller closes it and checks the result).
  hid_t release() { return std::exchange(id_, -1); }

private:
  hid_t id_;
  Closer close_;
};

inline void quiet_hdf5()
{
  static const bool done = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)done;
}

/// Why the last HDF5 call failed, from its error stack: the operating system's reason where the
/// failure was a read or write of the file ("No space left on device"), else HDF5's innermost
/// message ("incorrect metadata checksum after all read attempts"); empty if there is none.
inline std::string hdf5_reason()
{
  std::string reason;
  auto innermost = [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t
  {
    if (n == 0 && e->desc)
      *static_cast<std::string*>(out) = e->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost, &reason);
  // the POSIX driver's messages: "... errno = 28, error message = 'No space left on device', ..."
  const std::string key = "error message = '";
  if (const auto b = reason.find(key); b != std::string::npos)
    if (const auto e = reason.find('\'', b + key.size()); e != std::string::npos)
      return reason.substr(b + key.size(), e - b - key.size());
  return reason;
}

/// " (REASON)" for a message, or nothing.
inline std::string with_reason(const std::string& reason)
{
  return reason.empty() ? std::string() : " (" + reason + ")";
}

/// CRC-32 (zlib's, as Python's zlib.crc32) of @p bytes bytes.
inline std::uint32_t crc32_of(const void* data, std::size_t bytes)
{
  return std::uint32_t(crc32_z(crc32_z(0L, Z_NULL, 0), static_cast<const Bytef*>(data), bytes));
}

// why: the checksums are of the bytes in the file, little-endian, taken from memory as they are
static_assert(std::endian::native == std::endian::little, "checksums of memory in file order");

/// Keeps every link of a group in its object header, whose checksum HDF5 verifies, instead of
/// the dense storage (fractal heap and B-tree) HDF5 switches to above 8 links: HDF5 1.10's
/// iteration over dense links frees uninitialised pointers when their metadata fail the
/// checksum, so a damaged checkpoint crashed the resume instead of being refused. Takes a
/// group or file creation property list and returns it.
inline hid_t compact_links(hid_t creation)
{
  H5Pset_link_phase_change(creation, 65535, 65534);
  return creation;
}

inline constexpr const char* checksum_attribute = "crc32";

/// Attaches the checksum attribute to @p set; false if HDF5 failed.
inline bool write_checksum(hid_t set, std::uint32_t crc)
{
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(
      H5Acreate2(set, checksum_attribute, H5T_STD_U32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  return attr.ok() && H5Awrite(attr.get(), H5T_NATIVE_UINT32, &crc) >= 0;
}

/// Compares the checksum attribute of @p set with @p crc: "" when they agree, else why not.
inline std::string checksum_mismatch(hid_t set, std::uint32_t crc)
{
  if (H5Aexists(set, checksum_attribute) <= 0)
    return "no checksum (attribute '" + std::string(checksum_attribute) + "')" +
           with_reason(hdf5_reason());
  Handle attr(H5Aopen(set, checksum_attribute, H5P_DEFAULT), H5Aclose);
  std::uint32_t stored = 0;
  if (!attr.ok() || H5Aread(attr.get(), H5T_NATIVE_UINT32, &stored) < 0)
    return "its checksum cannot be read" + with_reason(hdf5_reason());
  if (stored != crc)
    return "its data do not match their checksum";
  return "";
}

/// The archive on an open HDF5 file: groups are HDF5 groups, arrays datasets of their
/// element type (little-endian in the file, converted on reading), Vec3 and Quat arrays
/// two-dimensional (n x 3, n x 4), strings fixed-length.
class Hdf5Archive : public dem::StateArchive
{
public:
  Hdf5Archive(hid_t file, bool loading, std::string name)
      : loading_(loading), name_(std::move(name))
  {
    stack_.push_back(file);
  }
  ~Hdf5Archive() override
  {
    for (std::size_t k = 1; k < stack_.size(); ++k)
      H5Gclose(stack_[k]);
  }

  bool loading() const override { return loading_; }
  std::string where() const override
  {
    std::string path = "/";
    for (const auto& p : path_)
      path += p + "/";
    return name_ + ": " + path;
  }
  void enter(const std::string& group) override
  {
    const hid_t here = stack_.back();
    hid_t g;
    if (loading_)
    {
      if (H5Lexists(here, group.c_str(), H5P_DEFAULT) <= 0)
        missing(group + "/");
      g = H5Gopen2(here, group.c_str(), H5P_DEFAULT);
    }
    else
    {
      const hid_t creation = compact_links(H5Pcreate(H5P_GROUP_CREATE));
      g = H5Gcreate2(here, group.c_str(), H5P_DEFAULT, creation, H5P_DEFAULT);
      H5Pclose(creation);
    }
    if (g < 0)
      failed(group + "/");
    stack_.push_back(g);
    path_.push_back(group);
  }
  void leave() override
  {
    H5Gclose(stack_.back());
    stack_.pop_back();
    path_.pop_back();
  }

  void io(const std::string& n, std::vector<double>& v) override
  {
    array(n, v, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, H5T_FLOAT, 1);
  }
  void io(const std::string& n, std::vector<std::int32_t>& v) override
  {
    array(n, v, H5T_STD_I32LE, H5T_NATIVE_INT32, H5T_INTEGER, 1);
  }
  void io(const std::string& n, std::vector<std::int64_t>& v) override
  {
    array(n, v, H5T_STD_I64LE, H5T_NATIVE_INT64, H5T_INTEGER, 1);
  }
  void io(const std::string& n, std::vector<std::uint8_t>& v) override
  {
    array(n, v, H5T_STD_U8LE, H5T_NATIVE_UINT8, H5T_INTEGER, 1);
  }
  void io(const std::string& n, std::vector<std::uint32_t>& v) override
  {
    array(n, v, H5T_STD_U32LE, H5T_NATIVE_UINT32, H5T_INTEGER, 1);
  }
  void io(const std::string& n, std::vector<dem::Vec3>& v) override
  {
    array(n, v, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, H5T_FLOAT, 3);
  }
  void io(const std::string& n, std::vector<dem::Quat>& v) override
  {
    // Eigen keeps (x, y, z, w); the file has (w, x, y, z), the usual order for scripts
    std::vector<double> wxyz(4 * v.size());
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      wxyz[4 * k] = v[k].w(), wxyz[4 * k + 1] = v[k].x();
      wxyz[4 * k + 2] = v[k].y(), wxyz[4 * k + 3] = v[k].z();
    }
    std::vector<std::array<double, 4>> rows(v.size());
    if (!wxyz.empty()) // why: memcpy with an empty vector's null data() is undefined (UBSan)
      std::memcpy(rows.data(), wxyz.data(), wxyz.size() * sizeof(double));
    array(n, rows, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, H5T_FLOAT, 4);
    if (loading_)
    {
      v.resize(rows.size());
      for (std::size_t k = 0; k < rows.size(); ++k)
        v[k] = dem::Quat(rows[k][0], rows[k][1], rows[k][2], rows[k][3]);
    }
  }
  void io(const std::string& n, std::string& text) override
  {
    const hid_t here = stack_.back();
    if (!loading_)
    {
      Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(type.get(), std::max<std::size_t>(1, text.size()));
      H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
      Handle space(H5Screate(H5S_SCALAR), H5Sclose);
      Handle set(H5Dcreate2(here, n.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT,
                            H5P_DEFAULT),
                 H5Dclose);
      std::string padded = text;
      padded.resize(std::max<std::size_t>(1, text.size()), '\0');
      if (!set.ok() || !write_checksum(set.get(), crc32_of(padded.data(), padded.size())) ||
          H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, padded.data()) < 0)
        failed(n);
      return;
    }
    Handle set = open(n);
    Handle type(H5Dget_type(set.get()), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0)
      wrong(n, "a fixed-length string");
    std::string buffer(H5Tget_size(type.get()), '\0');
    Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(memory.get(), buffer.size());
    H5Tset_strpad(memory.get(), H5T_STR_NULLPAD);
    if (H5Dread(set.get(), memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0)
      failed(n);
    check(set.get(), n, crc32_of(buffer.data(), buffer.size()));
    buffer.erase(buffer.find_last_not_of('\0') + 1);
    text = buffer;
  }

private:
  [[noreturn]] void missing(const std::string& n) const
  {
    throw InputError(where() + n + ": missing from the checkpoint (a file of another format?)");
  }
  [[noreturn]] void wrong(const std::string& n, const std::string& expected) const
  {
    throw InputError(where() + n + ": expected " + expected + " in the checkpoint");
  }
  [[noreturn]] void failed(const std::string& n) const
  {
    const std::string reason = with_reason(hdf5_reason());
    if (loading_) // why: a file that HDF5 cannot read is a damaged input, not a program error
      throw InputError(where() + n + ": damaged, HDF5 cannot read it" + reason);
    throw std::runtime_error(where() + n + ": HDF5 could not write it" + reason);
  }
  /// Refuses a dataset whose bytes are not those written (InputError naming it).
  void check(hid_t set, const std::string& n, std::uint32_t crc) const
  {
    const std::string mismatch = checksum_mismatch(set, crc);
    if (!mismatch.empty())
      throw InputError(where() + n + ": damaged: " + mismatch);
  }
  Handle open(const std::string& n)
  {
    const hid_t here = stack_.back();
    if (H5Lexists(here, n.c_str(), H5P_DEFAULT) <= 0)
      missing(n);
    Handle set(H5Dopen2(here, n.c_str(), H5P_DEFAULT), H5Dclose);
    if (!set.ok())
      failed(n);
    return set;
  }

  /// An array of T, each element `columns` values of the memory type (one row).
  template <class T>
  void array(const std::string& n, std::vector<T>& v, hid_t file_type, hid_t memory_type,
             H5T_class_t type_class, hsize_t columns)
  {
    // rows of plain doubles or integers (Eigen's Vector3d is three doubles without padding)
    static_assert(sizeof(T) % sizeof(double) == 0 || std::is_integral_v<T>);
    const hsize_t rank = columns > 1 ? 2 : 1;
    if (!loading_)
    {
      const hsize_t dims[2] = {hsize_t(v.size()), columns};
      Handle space(H5Screate_simple(int(rank), dims, nullptr), H5Sclose);
      Handle set(H5Dcreate2(stack_.back(), n.c_str(), file_type, space.get(), H5P_DEFAULT,
                            H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose);
      if (!set.ok() || !write_checksum(set.get(), crc32_of(v.data(), v.size() * sizeof(T))) ||
          (!v.empty() &&
           H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0))
        failed(n);
      return;
    }
    Handle set = open(n);
    Handle type(H5Dget_type(set.get()), H5Tclose);
    Handle space(H5Dget_space(set.get()), H5Sclose);
    hsize_t dims[2] = {0, 0};
    const int found_rank = H5Sget_simple_extent_ndims(space.get());
    if (H5Tget_class(type.get()) != type_class || found_rank != int(rank))
      wrong(n, std::string(type_class == H5T_FLOAT ? "floating-point" : "integer") + " data of " +
                   std::to_string(rank) + " dimension(s)");
    H5Sget_simple_extent_dims(space.get(), dims, nullptr);
    if (rank == 2 && dims[1] != columns)
      wrong(n, std::to_string(columns) + " columns");
    v.resize(std::size_t(dims[0]));
    if (!v.empty() && H5Dread(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
      failed(n);
    check(set.get(), n, crc32_of(v.data(), v.size() * sizeof(T)));
  }

  bool loading_;
  std::string name_;
  std::vector<hid_t> stack_;
  std::vector<std::string> path_;
};
} // namespace dembridge::app::hdf5
