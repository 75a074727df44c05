#pragma once
// What the checkpoint tests share (test_checkpoint.cc, test_checkpoint_integrity.cc): a
// scratch folder, a set of fields of every type the checkpoint stores, a checkpoint shaped like
// a run's, a header, and the message of the InputError a call throws.
#include "app/checkpoint/checkpoint.h"
#include "dem/core/types.h"
#include <cstdint>
#include <filesystem>
#include <functional>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace checkpoint_test
{
using namespace dembridge;
namespace fs = std::filesystem;

inline fs::path scratch(const std::string& name)
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

inline app::CheckpointHeader header()
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
inline void set_format_version(const fs::path& file, std::int32_t version)
{
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t attr = H5Aopen(f, "format_version", H5P_DEFAULT);
  ASSERT_GE(attr, 0);
  EXPECT_GE(H5Awrite(attr, H5T_NATIVE_INT32, &version), 0);
  H5Aclose(attr);
  H5Fclose(f);
}

inline std::string error_of(const std::function<void()>& f)
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
} // namespace checkpoint_test
