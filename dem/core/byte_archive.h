#pragma once
// A StateArchive in memory: the fields a visit names, packed into one string in the order it
// names them (saving) and unpacked from it in that order (loading), each with its name, which
// must match. A coupled run on several MPI ranks hands rank 0's restored state to the other
// ranks this way (fem/explicit_dynamics.h, broadcast_state): the same visit on every rank.
#include "dem/core/state_archive.h"
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace dembridge::dem
{
class ByteArchive : public StateArchive
{
public:
  /// Saving: the fields go to bytes().
  ByteArchive() = default;
  /// Loading: the fields come from @p bytes (another ByteArchive's bytes()).
  explicit ByteArchive(std::string bytes) : loading_(true), bytes_(std::move(bytes)) {}

  const std::string& bytes() const { return bytes_; }
  bool loading() const override { return loading_; }
  void enter(const std::string& group) override { path_.push_back(group); }
  void leave() override { path_.pop_back(); }
  std::string where() const override
  {
    std::string path = "state/";
    for (const auto& p : path_)
      path += p + "/";
    return path;
  }

  void io(const std::string& n, std::vector<double>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<std::int32_t>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<std::int64_t>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<std::uint8_t>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<std::uint32_t>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<Vec3>& v) override { field(n, v); }
  void io(const std::string& n, std::vector<Quat>& v) override { field(n, v); }
  void io(const std::string& n, std::string& text) override { field(n, text); }

private:
  /// A name, a count and the elements' bytes (fixed-size plain values: doubles, integers,
  /// Eigen's fixed vectors and quaternions).
  template <class Container> void field(const std::string& name, Container& v)
  {
    using T = typename Container::value_type;
    static_assert(std::is_trivially_destructible_v<T>);
    if (!loading_)
    {
      put(name.size()), bytes_ += name;
      put(v.size());
      bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
      return;
    }
    const std::size_t length = get();
    need(length, name);
    // why: both sides run the same visit; another name is a program error, not bad input
    if (bytes_.compare(at_, length, name) != 0)
      throw std::logic_error(where() + name + ": the visits name other fields");
    at_ += length;
    const std::size_t n = get();
    need(n * sizeof(T), name);
    v.resize(n);
    if (n > 0) // why: memcpy from or to the null data() of an empty vector is undefined
      std::memcpy(static_cast<void*>(v.data()), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
  }
  void put(std::size_t n) { bytes_.append(reinterpret_cast<const char*>(&n), sizeof n); }
  std::size_t get()
  {
    need(sizeof(std::size_t), "(count)");
    std::size_t n;
    std::memcpy(&n, bytes_.data() + at_, sizeof n);
    at_ += sizeof n;
    return n;
  }
  void need(std::size_t n, const std::string& name) const
  {
    if (bytes_.size() - at_ < n)
      throw std::logic_error(where() + name + ": past the end of the packed state");
  }

  bool loading_ = false;
  std::string bytes_;
  std::size_t at_ = 0;
  std::vector<std::string> path_;
};
} // namespace dembridge::dem
