// Inputs the DEM core must not take silently: particle files with comments and named
// columns in any order, overlapping spheres in a file, a `nearest` point far outside the
// specimen, a load on DOFs that every particle of its group holds fixed. Each refusal is one
// line that names the file or key and the reason.
#include "dem/model/load_checks.h"
#include "dem/model/model.h"
#include "dem/packing/packings.h"
#include <gtest/gtest.h>
#include <sstream>

using namespace dembridge::dem;

namespace
{
ParticleStore read(const std::string& text)
{
  std::istringstream in(text);
  ParticleStore p;
  read_particles(in, "test.csv", 1000, p);
  return p;
}

std::string error_of(const std::string& text)
{
  try
  {
    read(text);
  }
  catch (const InputError& e)
  {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    return e.what();
  }
  return "no error";
}

/// A row of three touching spheres r = 0.1 m along x, the first held, a load on the last.
CaseConfig row_with_load(std::uint8_t tip_fixed, LoadKind kind, Vec3 value)
{
  CaseConfig c;
  c.particles.count = 3;
  c.particles.radius = 0.1;
  c.bonds.material.youngs_modulus = 1e9;
  c.bonds.material.poisson_ratio = 0.3;
  GroupConfig clamp{"clamp", {}, 63, 0, Vec3::Zero()};
  clamp.selection.kind = GroupSelection::Kind::index;
  clamp.selection.indices = {0};
  GroupConfig tip{"tip", {}, tip_fixed, 0, Vec3::Zero()};
  tip.selection.kind = GroupSelection::Kind::index;
  tip.selection.indices = {-1};
  c.groups = {clamp, tip};
  LoadConfig load;
  load.load.name = "push";
  load.load.kind = kind;
  load.load.value = value;
  load.load.components = 0b101; // x, z (prescribed motions)
  load.load.ramp_time = 1;
  load.group = "tip";
  c.loads = {load};
  return c;
}
} // namespace

// '#' comments anywhere, a header naming the columns in another order, ';' or blanks as
// separators: the values land in x, y, z, r by name.
TEST(ParticleFile, NamedColumnsInAnyOrder)
{
  const ParticleStore p = read("# made by hand\n\n  # indented comment\n"
                               "R; z; X; y   # header with a comment\n"
                               "0.01; 3; 1; 2\n"
                               "0.02 6 4 5 # trailing comment\n");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p.position[0], Vec3(1, 2, 3));
  EXPECT_EQ(p.position[1], Vec3(4, 5, 6));
  EXPECT_EQ(p.radius[0], 0.01);
  EXPECT_EQ(p.radius[1], 0.02);
  const ParticleStore q = read("x, y, z, radius\n0, 0, 0, 0.5\n");
  EXPECT_EQ(q.radius[0], 0.5);
  const ParticleStore plain = read("0, 0, 0, 0.5\n1.5, 0, 0, 0.5\n"); // no header: x, y, z, r
  EXPECT_EQ(plain.position[1], Vec3(1.5, 0, 0));
}

// A header that cannot be read by name is refused with the reason and the line.
TEST(ParticleFile, BadHeadersAreRefused)
{
  EXPECT_EQ(error_of("# c\nx, y, z, id\n0,0,0,1\n"),
            "test.csv:2: unknown column 'id' in the header (expected x, y, z and r, in any order)");
  EXPECT_EQ(error_of("x, y, x, r\n0,0,0,1\n"), "test.csv:1: the header names column 'x' twice");
  EXPECT_EQ(error_of("x, y, z\n0,0,0\n"), "test.csv:1: the header lacks column 'r'");
  EXPECT_EQ(error_of("0,0,0,1\nx, y, z, r\n"),
            "test.csv:2: expected four numbers 'x, y, z, r' (m)");
}

// Overlaps: up to 1 % of the smaller radius is accepted (a packing saved by the random packer
// overlaps by 1e-4), more is refused naming the pair, their lines and the amount.
TEST(ParticleFile, OverlapsBeyondOnePercentAreRefused)
{
  EXPECT_EQ(read("x,y,z,r\n0,0,0,1\n1.991,0,0,1\n").size(), 2u); // 0.9 %
  EXPECT_EQ(error_of("x,y,z,r\n0,0,0,1\n# between\n1.989,0,0,1\n"),
            "test.csv: particles 0 and 1 (lines 2 and 4) overlap by 1.1 % of the smaller radius "
            "(at most 1 % is accepted)");
  EXPECT_EQ(error_of("0,0,0,1\n0,0,0,1\n"),
            "test.csv: particles 0 and 1 sit at the same position (lines 1 and 2)");
}

// A `nearest` point a tenth of the specimen's diagonal or more outside its bounding box is
// refused with the distance (here: the point given in mm instead of m); a corner is accepted.
TEST(Groups, NearestPointFarOutsideIsRefused)
{
  ParticleStore p;
  for (int i = 0; i < 10; ++i)
    p.add(Vec3(0.01 + 0.02 * i, 0.01, 0.01), 0.01, 1000);
  GroupSelection s;
  s.kind = GroupSelection::Kind::nearest;
  s.point = Vec3(0, 0, 0);
  EXPECT_EQ(select_group(p, "corner", s, "Group corner/select").members, std::vector<int>{0});
  s.point = Vec3(200, 20, 20);
  try
  {
    select_group(p, "corner", s, "Group corner/select");
    FAIL() << "not refused";
  }
  catch (const InputError& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind("Group corner/point: (200, 20, 20) lies 201.8 m outside "
                                          "the specimen",
                                          0),
              0u)
        << e.what();
  }
}

// Loads act on DOFs: a force on its non-zero components' translations, a moment on rotations,
// a prescribed motion on its prescribed components.
TEST(LoadChecks, LoadDofs)
{
  Load l;
  l.value = Vec3(0, 0, -1);
  EXPECT_EQ(load_dofs(l), dof_uz);
  l.kind = LoadKind::moment;
  l.value = Vec3(1, 2, 0);
  EXPECT_EQ(load_dofs(l), dof_rx | dof_ry);
  l.kind = LoadKind::displacement;
  l.components = 0b011;
  EXPECT_EQ(load_dofs(l), dof_ux | dof_uy);
  l.kind = LoadKind::angular_velocity;
  EXPECT_EQ(load_dofs(l), dof_rx | dof_ry);
}

// A load whose DOFs are all held on every particle of its group is refused; one free DOF is
// enough to accept it.
TEST(LoadChecks, LoadOnFixedDofsIsRefused)
{
  EXPECT_NO_THROW(build_model(row_with_load(0, LoadKind::force, Vec3(0, 0, -1))));
  EXPECT_NO_THROW(build_model(row_with_load(dof_uz, LoadKind::force, Vec3(1, 0, -1))));
  try
  {
    build_model(row_with_load(dof_uz, LoadKind::force, Vec3(0, 0, -1)));
    FAIL() << "not refused";
  }
  catch (const InputError& e)
  {
    EXPECT_STREQ(e.what(), "Load push/group: every DOF the load acts on (uz) is held by a support "
                           "on every particle of group 'tip', so the load would only load the "
                           "support");
  }
  EXPECT_THROW(build_model(row_with_load(dof_ux | dof_uz, LoadKind::displacement, Vec3(1, 0, 1))),
               InputError);
  EXPECT_NO_THROW(build_model(row_with_load(dof_ux, LoadKind::displacement, Vec3(1, 0, 1))));
}
