#pragma once
// The state of a run as named arrays, for checkpoints (app/checkpoint/checkpoint.h writes them to HDF5,
// docs/checkpoint.md lists them). Every class that holds run state has one visit function that
// names its fields; the same function saves (the archive reads the references) and restores
// (the archive writes into them), so saving and restoring cannot drift apart.
// The DEM layer knows nothing of the file format: the archive is an interface, called once per
// field at a checkpoint, never inside a step.
#include "dem/core/types.h"
#include <cstdint>
#include <string>
#include <vector>

namespace dembridge::dem
{
class StateArchive
{
public:
  virtual ~StateArchive() = default;
  /// True while restoring: the visit functions' references receive the stored values.
  virtual bool loading() const = 0;
  /// Fields named after enter() belong to the group (nested as in a file system).
  virtual void enter(const std::string& group) = 0;
  virtual void leave() = 0;

  virtual void io(const std::string& name, std::vector<double>& v) = 0;
  virtual void io(const std::string& name, std::vector<std::int32_t>& v) = 0;
  virtual void io(const std::string& name, std::vector<std::int64_t>& v) = 0;
  virtual void io(const std::string& name, std::vector<std::uint8_t>& v) = 0;
  virtual void io(const std::string& name, std::vector<std::uint32_t>& v) = 0;
  /// Rows of three (x, y, z).
  virtual void io(const std::string& name, std::vector<Vec3>& v) = 0;
  /// Rows of four (w, x, y, z).
  virtual void io(const std::string& name, std::vector<Quat>& v) = 0;
  virtual void io(const std::string& name, std::string& text) = 0;

  // Scalars, stored as one-element arrays.
  void io(const std::string& name, double& x) { scalar<double>(name, x); }
  void io(const std::string& name, long& x) { scalar<std::int64_t>(name, x); }
  void io(const std::string& name, int& x) { scalar<std::int32_t>(name, x); }
  void io(const std::string& name, std::size_t& x) { scalar<std::int64_t>(name, x); }
  void io(const std::string& name, bool& x) { scalar<std::uint8_t>(name, x); }
  void io(const std::string& name, Vec3& x)
  {
    std::vector<Vec3> v{x};
    io(name, v);
    x = expect_one(name, v);
  }
  /// A vector of 8-bit enums (BondState, CrackMode, ...).
  template <class Enum> void io_enums(const std::string& name, std::vector<Enum>& v)
  {
    static_assert(sizeof(Enum) == 1);
    std::vector<std::uint8_t> raw(v.size());
    for (std::size_t k = 0; k < v.size(); ++k)
      raw[k] = std::uint8_t(v[k]);
    io(name, raw);
    v.resize(raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k)
      v[k] = Enum(raw[k]);
  }
  /// Like io(name, v), but a restored array must have the length v has now (the rebuilt model's
  /// particles or bonds): a checkpoint of another model is refused, not half applied.
  template <class T> void io_sized(const std::string& name, std::vector<T>& v)
  {
    const std::size_t n = v.size();
    io(name, v);
    if (loading() && v.size() != n)
      throw InputError(where() + name + ": " + std::to_string(v.size()) +
                       " entries in the checkpoint, " + std::to_string(n) + " in this model");
  }
  /// The current group path with a trailing '/' (for messages).
  virtual std::string where() const = 0;

private:
  template <class Stored, class T> void scalar(const std::string& name, T& x)
  {
    std::vector<Stored> v{Stored(x)};
    io(name, v);
    x = T(expect_one(name, v));
  }
  template <class T> T expect_one(const std::string& name, const std::vector<T>& v)
  {
    if (v.size() != 1)
      throw InputError(where() + name + ": expected one value in the checkpoint, found " +
                       std::to_string(v.size()));
    return v[0];
  }
};

/// Opens a group for the lifetime of the object.
class StateGroup
{
public:
  StateGroup(StateArchive& a, const std::string& name) : a_(a) { a_.enter(name); }
  ~StateGroup() { a_.leave(); }
  StateGroup(const StateGroup&) = delete;
  StateGroup& operator=(const StateGroup&) = delete;

private:
  StateArchive& a_;
};
} // namespace dembridge::dem
