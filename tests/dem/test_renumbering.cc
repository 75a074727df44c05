// Spatial renumbering at setup (dem/model/renumbering.h): the same specimen built with
// and without it is the same physical model; only the order of floating-point sums differs.
//  - static solves: the same end displacements, E and nu to solver tolerance (CG to 1e-10: 1e-8
//    relative) on an HCP lattice and a random packing;
//  - an explicit run to bond failure with strengths scattered in bond order (Damage/scatter key
//    = bond order): every physical bond keeps its strengths bit for bit, and the run (on 1
//    thread as built, on 2 renumbered) breaks the same bonds (by user ids) at the same steps,
//    with the same displacements to 1e-9;
//  - user-visible numbering: ParticleStore::id, index and nearest groups name the same
//    particles;
//  - the order is spatial: consecutive bonds share particles and two threads' index chunks cut
//    few bonds (under 1/10, against about half in a shuffled order), and it depends only on
//    the positions (a shuffled specimen renumbers to the same order);
//  - renumbered random packings are reproducible from their seed, bit for bit.
#include "dem/measurements/measurements.h"
#include "dem/model/model.h"
#include "dem/model/renumbering.h"
#include "dem/solvers/bond_partition.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/static_solver.h"
#include "face_group.h"
#include <algorithm>
#include <gtest/gtest.h>
#include <map>
#include <numeric>
#include <random>

using namespace dembridge::dem;

namespace
{
using Kind = ParticleSource::Kind;

using dembridge::test::face_group;

/// Uniaxial compression along x of a small specimen (r = 2.5 mm): the x- face held in all six
/// DOFs, the x+ face pushed 1 um along x (free across); static solver.
CaseConfig compression(Kind kind, bool spatial_order)
{
  CaseConfig c;
  c.particles.kind = kind;
  c.particles.radius = 2.5e-3;
  c.particles.box_size = Vec3(0.06, 0.03, 0.03);
  c.particles.seed = 5;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.contact_radius_multiplier = kind == Kind::random ? 1.04 : 1.0;
  c.groups = {face_group("fixed", 0, false, 63), face_group("loaded", 0, true, 0)};
  Load push;
  push.name = "push";
  push.kind = LoadKind::displacement;
  push.value = Vec3(-1e-6, 0, 0);
  push.components = 1;
  push.ramp_time = 1;
  c.loads = {{push, "loaded", ""}};
  c.run.static_solver = true;
  c.spatial_order = spatial_order;
  return c;
}

/// Position of each particle by user id.
std::vector<Vec3> by_id(const ParticleStore& p, const std::vector<Vec3>& field)
{
  std::vector<Vec3> out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    out[std::size_t(p.id[i])] = field[i];
  return out;
}

double relative_difference(const std::vector<Vec3>& x, const std::vector<Vec3>& y)
{
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < y.size(); ++i)
    diff = std::max(diff, (x[i] - y[i]).norm()), scale = std::max(scale, y[i].norm());
  return diff / scale;
}

std::vector<Vec3> displacements(const ParticleStore& p)
{
  std::vector<Vec3> u(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    u[i] = p.position[i] - p.reference_position[i];
  return by_id(p, u);
}

class Renumbering : public ::testing::TestWithParam<Kind>
{
};

TEST_P(Renumbering, StaticCompressionGivesTheSameModulusAndDisplacements)
{
  StaticSettings settings;
  settings.method = StaticSettings::Method::cg_jacobi;
  settings.cg_tolerance = 1e-10;
  Model as_built = build_model(compression(GetParam(), false));
  Model ordered = build_model(compression(GetParam(), true));
  ASSERT_EQ(as_built.particles.size(), ordered.particles.size());
  ASSERT_EQ(as_built.bonds.size(), ordered.bonds.size());
  EXPECT_LT(solve_static(as_built, settings).residual, 1e-9);
  EXPECT_LT(solve_static(ordered, settings).residual, 1e-9);
  EXPECT_LT(
      relative_difference(displacements(ordered.particles), displacements(as_built.particles)),
      1e-8);
  auto response = [](const Model& m)
  { return axial_response(m.particles, m.groups[0], m.groups[1], 0); };
  const AxialResponse a = response(as_built), b = response(ordered);
  EXPECT_GT(a.youngs_modulus, 1e8);
  EXPECT_NEAR(b.youngs_modulus, a.youngs_modulus, 1e-8 * a.youngs_modulus);
  for (int d : {1, 2})
    EXPECT_NEAR(b.poisson_ratio[d], a.poisson_ratio[d], 1e-8);
  EXPECT_GT(a.poisson_ratio[1], 0.01); // a lateral strain to compare
}

INSTANTIATE_TEST_SUITE_P(LatticeAndRandom, Renumbering, ::testing::Values(Kind::hcp, Kind::random),
                         [](const auto& info)
                         { return std::string(info.param == Kind::hcp ? "hcp" : "random"); });

/// Tension to failure of a random specimen, brittle bonds, normal scatter in bond order.
CaseConfig tension_to_failure(bool spatial_order)
{
  CaseConfig c = compression(Kind::random, spatial_order);
  c.run.static_solver = false;
  c.loads[0].load.kind = LoadKind::velocity;
  c.loads[0].load.value = Vec3(0.05, 0, 0);
  c.loads[0].load.ramp_time = 0;
  c.damage.law.mode = FailureMode::brittle;
  c.damage.tensile_strength = 2e5;
  c.damage.shear_strength = 4e5;
  c.damage.scatter = StrengthScatter::normal;
  c.damage.scatter_deviation = 0.3;
  c.damage.seed = 11;
  c.damage.scatter_by_position = false; // bond order: the draws follow formation order
  return c;
}

TEST(RenumberingDamage, SameStrengthsPerBondAndTheSameCracks)
{
  Model as_built = build_model(tension_to_failure(false));
  Model ordered = build_model(tension_to_failure(true));
  // strengths by the bond's particles in the user's numbering
  auto strengths = [](const Model& m)
  {
    std::map<std::pair<int, int>, std::pair<double, double>> s;
    for (std::size_t k = 0; k < m.bonds.size(); ++k)
      s[{m.particles.id[m.bonds.a[k]], m.particles.id[m.bonds.b[k]]}] = {
          m.bonds.tensile_strength[k], m.bonds.shear_strength[k]};
    return s;
  };
  ASSERT_EQ(strengths(as_built), strengths(ordered)); // bit for bit, every bond
  const double dt = 0.5 * as_built.critical.critical();
  ASSERT_EQ(dt, 0.5 * ordered.critical.critical());
  ExplicitSolver s1(as_built.particles, as_built.bonds, as_built.groups, as_built.constraints,
                    as_built.loads, {dt, 0.0, 1});
  ExplicitSolver s2(ordered.particles, ordered.bonds, ordered.groups, ordered.constraints,
                    ordered.loads, {dt, 0.0, 2});
  for (int step = 0; step < 3000; ++step)
  {
    s1.step(step % 100 == 0);
    s2.step(step % 100 == 0);
  }
  ASSERT_GT(s1.n_broken_bonds(), 3); // the test reaches failure
  ASSERT_EQ(s1.n_broken_bonds(), s2.n_broken_bonds());
  for (std::size_t k = 0; k < s1.cracks().size(); ++k)
  {
    const auto &c1 = s1.cracks()[k], &c2 = s2.cracks()[k];
    EXPECT_EQ(c1.a, c2.a); // user ids, in the same order
    EXPECT_EQ(c1.b, c2.b);
    EXPECT_EQ(c1.time, c2.time);
    // a bond's energy at failure, U ~ k d^2 / 2 with d ~ 2.5e-7 m: position round-off of
    // ~1e-16 m after 3000 steps is ~1e-9 of it
    EXPECT_NEAR(c2.energy, c1.energy, 1e-8 * c1.energy);
  }
  EXPECT_LT(
      relative_difference(displacements(ordered.particles), displacements(as_built.particles)),
      1e-9);
  EXPECT_NEAR(s2.energy().strain, s1.energy().strain, 1e-9 * s1.energy().strain);
  EXPECT_NEAR(s2.energy().fracture, s1.energy().fracture, 1e-9 * s1.energy().fracture);
}

TEST(RenumberingIds, GroupsNameTheUsersParticles)
{
  CaseConfig c = compression(Kind::random, true);
  GroupConfig picked{"picked", {}, 0, 0, Vec3::Zero()};
  picked.selection.kind = GroupSelection::Kind::index;
  picked.selection.indices = {0, 7, -1};
  GroupConfig nearest{"nearest", {}, 0, 0, Vec3::Zero()};
  nearest.selection.kind = GroupSelection::Kind::nearest;
  nearest.selection.point = Vec3(0.03, 0.015, 0.015);
  c.groups.push_back(picked);
  c.groups.push_back(nearest);
  CaseConfig plain = c;
  plain.spatial_order = false;
  const Model m = build_model(c), reference = build_model(plain);
  const std::size_t n = m.particles.size();
  std::vector<int> ids;
  for (int i : m.groups[2].members)
    ids.push_back(m.particles.id[std::size_t(i)]);
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<int>{0, 7, int(n) - 1}));
  const int near = m.groups[3].members.at(0), near_plain = reference.groups[3].members.at(0);
  EXPECT_EQ(m.particles.id[std::size_t(near)], near_plain);
  EXPECT_EQ(m.particles.reference_position[std::size_t(near)],
            reference.particles.reference_position[std::size_t(near_plain)]);
  // ids are a permutation, and each particle keeps its own data
  std::vector<char> seen(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto id = std::size_t(m.particles.id[i]);
    ASSERT_LT(id, n);
    EXPECT_FALSE(seen[id]);
    seen[id] = 1;
    EXPECT_EQ(m.particles.reference_position[i], reference.particles.reference_position[id]);
    EXPECT_EQ(m.particles.radius[i], reference.particles.radius[id]);
    EXPECT_EQ(m.particles.coordination[i], reference.particles.coordination[id]);
  }
}

/// Share of the bonds that join the two index halves (the two threads' chunks).
double cut_share(const Model& m)
{
  const auto part = partition_bonds_by_index(m.bonds.a, m.bonds.b, m.particles.size(), 2);
  const auto [first, last] = part.phases[1].at(0);
  return double(last - first) / double(m.bonds.size());
}

TEST(RenumberingOrder, BondsShareParticlesAndThreadsCutFewBonds)
{
  CaseConfig c = compression(Kind::random, true);
  c.run.static_solver = false;
  const Model m = build_model(c);
  // consecutive bonds share their lower particle: runs of about half the coordination
  long runs = 1;
  for (std::size_t k = 1; k < m.bonds.size(); ++k)
    runs += std::min(m.bonds.a[k], m.bonds.b[k]) != std::min(m.bonds.a[k - 1], m.bonds.b[k - 1]);
  EXPECT_GT(double(m.bonds.size()) / double(runs), 2.5);
  EXPECT_LT(cut_share(m), 0.1);
  // the same specimen in a seeded random order: the halves cut about half the bonds; renumbered
  // again, it comes back to the same order (the order is a function of the positions)
  Model shuffled = m;
  std::vector<std::size_t> order(m.particles.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::shuffle(order.begin(), order.end(), std::mt19937_64(3));
  renumber_particles(shuffled.particles, shuffled.bonds, &shuffled.groups, order);
  EXPECT_GT(cut_share(shuffled), 0.4);
  renumber_spatially(shuffled.particles, shuffled.bonds, &shuffled.groups);
  EXPECT_EQ(shuffled.particles.id, m.particles.id);
  EXPECT_EQ(shuffled.bonds.a, m.bonds.a);
  EXPECT_EQ(shuffled.bonds.b, m.bonds.b);
  EXPECT_EQ(shuffled.groups[1].members, m.groups[1].members);
}

TEST(RenumberingOrder, RandomPackingsAreReproducibleFromTheirSeed)
{
  CaseConfig c = compression(Kind::random, true);
  const Model m1 = build_model(c), m2 = build_model(c);
  ASSERT_EQ(m1.particles.size(), m2.particles.size());
  EXPECT_EQ(m1.particles.position, m2.particles.position);
  EXPECT_EQ(m1.particles.radius, m2.particles.radius);
  EXPECT_EQ(m1.particles.id, m2.particles.id);
  EXPECT_EQ(m1.bonds.a, m2.bonds.a);
  EXPECT_EQ(m1.bonds.b, m2.bonds.b);
  c.particles.seed = 6; // and another seed is another packing
  const Model m3 = build_model(c);
  EXPECT_NE(m1.particles.position, m3.particles.position);
}
} // namespace
