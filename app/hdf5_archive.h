#pragma once
// The checkpoint's HDF5 side (docs/checkpoint.md): a scoped HDF5 handle and dem::StateArchive
// on an open HDF5 file. Included by checkpoint.cc only (HDF5's C API stays out of the rest of
// the app).
#include "dem/core/state_archive.h"
#include <hdf5.h>
#include <stdexcept>
#include <string>
#include <vector>

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

private:
  hid_t id_;
  Closer close_;
};

inline void quiet_hdf5()
{
  static const bool done = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)done;
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
      g = H5Gcreate2(here, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
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
      if (!set.ok() ||
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
    throw std::runtime_error(where() + n + ": HDF5 could not " +
                             (loading_ ? "read it" : "write it (disk full?)"));
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
      if (!set.ok() || (!v.empty() && H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL,
                                               H5P_DEFAULT, v.data()) < 0))
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
  }

  bool loading_;
  std::string name_;
  std::vector<hid_t> stack_;
  std::vector<std::string> path_;
};
} // namespace dembridge::app::hdf5
