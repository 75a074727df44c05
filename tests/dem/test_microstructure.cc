// The microstructure (dem/microstructure/): weak planes against springs in series on the simple
// cubic lattice (microstructure.h eq. 1, exact), columnar grains against their definition
// (nearest seed in the plane, eq. 1-2 of columnar_grains.h), bond classes and their constants,
// and the inputs refused with one line.
#include "dem/microstructure/microstructure.h"
#include "dem/model/model.h"
#include "dem/solvers/static_solver.h"
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <map>
#include <numbers>
#include <set>

using namespace dembridge::dem;

namespace
{
constexpr double radius = 1e-3; // m

/// A simple cubic lattice of 13 x 4 x 4 particles (12 bonds along each x-chain), TBBM.
CaseConfig cubic_block()
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::cubic;
  c.particles.radius = radius;
  c.particles.box_size = Vec3(26 * radius, 8 * radius, 8 * radius);
  c.bonds.material.model = BondModel::timoshenko;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.run.static_solver = true;
  return c;
}

/// The reaction along @p axis of a static uniaxial strain test: the lower face held in every
/// DOF, the upper face displaced by 1 um along the axis (its translations prescribed).
double axial_reaction(CaseConfig c, int axis)
{
  GroupConfig held{"held", {}, 63, 0, Vec3::Zero()};
  held.selection.kind = GroupSelection::Kind::face;
  held.selection.face_axis = axis;
  held.selection.face_upper = false;
  GroupConfig pulled = held;
  pulled.name = "pulled";
  pulled.fixed = 0;
  pulled.selection.face_upper = true;
  c.groups = {held, pulled};
  LoadConfig load;
  load.group = "pulled";
  load.load.name = "stretch";
  load.load.kind = LoadKind::displacement;
  load.load.value = 1e-6 * Vec3::Unit(axis);
  load.load.components = dof_ux | dof_uy | dof_uz;
  c.loads = {load};
  Model m = build_model(c);
  StaticSettings direct;
  direct.method = StaticSettings::Method::direct;
  const StaticResult r = solve_static(m, direct);
  EXPECT_LT(r.residual, 1e-12);
  double force = 0;
  for (int i : m.groups[std::size_t(m.group_index("pulled", "test"))].members)
    force += m.particles.force[std::size_t(i)][axis];
  return force;
}

/// Planes normal to x between layers 0 and 1, then every n layers; their bonds alpha as stiff.
CaseConfig with_weak_planes(int n, double alpha)
{
  CaseConfig c = cubic_block();
  WeakPlaneSet planes;
  planes.normal = Vec3::UnitX();
  planes.offsets = {2 * radius}; // layer centres at r + 2 r i
  planes.spacing = n * 2 * radius;
  c.microstructure.weak_planes = planes;
  BondClassConfig weak = BondClassConfig::of_specimen(c.bonds.material, c.damage);
  weak.material.youngs_modulus *= alpha;
  c.microstructure.weak_plane = weak;
  return c;
}
} // namespace

// microstructure.h eq. (1): 1/E_x = (1/E)(1 - 1/n + 1/(alpha n)), E_y and E_z unchanged, to
// the direct solve's round-off.
class SpringsInSeries : public ::testing::TestWithParam<std::pair<int, double>>
{
};

TEST_P(SpringsInSeries, WeakPlanesSoftenOnlyTheirNormal)
{
  const auto [n, alpha] = GetParam();
  const CaseConfig plain = cubic_block(), planes = with_weak_planes(n, alpha);
  const Model m = build_model(planes);
  // every x-chain of 12 bonds crosses 12/n planes; 16 chains
  EXPECT_EQ(m.microstructure.bonds_per_class[std::size_t(BondClass::weak_plane)],
            std::size_t(16 * 12 / n));
  const double expected = 1.0 / (1.0 - 1.0 / n + 1.0 / (alpha * n)); // E_x / E
  const double ex = axial_reaction(planes, 0) / axial_reaction(plain, 0);
  const double ey = axial_reaction(planes, 1) / axial_reaction(plain, 1);
  const double ez = axial_reaction(planes, 2) / axial_reaction(plain, 2);
  std::cout << "n = " << n << ", alpha = " << alpha << ": E_x/E = " << ex << " (eq. 1: " << expected
            << ", rel. error " << ex / expected - 1 << "), E_y/E - 1 = " << ey - 1
            << ", E_z/E - 1 = " << ez - 1 << "\n";
  EXPECT_NEAR(ex / expected, 1.0, 1e-9);
  EXPECT_NEAR(ey, 1.0, 1e-9);
  EXPECT_NEAR(ez, 1.0, 1e-9);
}
INSTANTIATE_TEST_SUITE_P(TwoPlaneSets, SpringsInSeries,
                         ::testing::Values(std::pair{3, 0.2}, std::pair{4, 0.05}));

namespace
{
ColumnarGrainsConfig columns(double diameter, double jitter)
{
  ColumnarGrainsConfig g;
  g.enabled = true;
  g.diameter = diameter;
  g.jitter = jitter;
  g.seed = 7;
  return g;
}

/// Points of a square raster of n x n in [0, size]^2 (z = 0), radius tiny.
std::pair<std::vector<Vec3>, std::vector<double>> raster(int n, double size)
{
  std::vector<Vec3> x;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      x.emplace_back((i + 0.5) * size / n, (j + 0.5) * size / n, 0.0);
  return {x, std::vector<double>(x.size(), 1e-6)};
}
} // namespace

// A particle's column is the nearest seed in the plane: against a brute-force search over
// every node within ten lattice spacings, on a jittered lattice (the farthest seeds move most).
TEST(ColumnarGrains, ColumnIsTheNearestSeedInThePlane)
{
  for (double jitter : {0.0, 0.5, 1.0})
  {
    const ColumnarGrainsConfig g = columns(0.01, jitter);
    const auto [x, r] = raster(120, 0.06);
    const GrainMap map = assign_grains(x, r, g);
    const double a = column_lattice_spacing(g.diameter);
    long wrong = 0;
    for (std::size_t p = 0; p < x.size(); ++p)
    {
      double best = 1e300;
      std::array<double, 2> nearest{};
      const long jc = std::lround(x[p].y() / (a * std::sqrt(3.0) / 2));
      const long ic = std::lround(x[p].x() / a - 0.5 * double(jc));
      for (long j = jc - 10; j <= jc + 10; ++j)
        for (long i = ic - 10; i <= ic + 10; ++i)
        {
          const auto s = column_seed(g, i, j);
          const double d2 = std::pow(s[0] - x[p].x(), 2) + std::pow(s[1] - x[p].y(), 2);
          if (d2 < best)
            best = d2, nearest = s;
        }
      const Vec3& seed = map.grains[std::size_t(map.of_particle[p])].seed;
      wrong += seed.x() != nearest[0] || seed.y() != nearest[1];
    }
    EXPECT_EQ(wrong, 0) << "jitter " << jitter;
  }
}

// Eq. (1): each seed owns on average the area pi D^2 / 4. On a raster, the columns whose seeds
// lie at least two spacings inside: their mean area within three standard errors of the sample
// (sd / sqrt(N)) and 0.2 % (the raster's resolution, 40 points across a column); the
// equivalent diameters' coefficient of variation is printed (docs/microstructure.md).
TEST(ColumnarGrains, MeanColumnAreaIsThatOfTheDiameter)
{
  const double D = 0.01, size = 0.2;
  const auto [x, r] = raster(800, size);
  const double cell = std::pow(size / 800, 2);
  for (double jitter : {0.0, 0.3, 0.5, 1.0})
  {
    const ColumnarGrainsConfig g = columns(D, jitter);
    const GrainMap map = assign_grains(x, r, g);
    std::vector<long> count(map.grains.size(), 0);
    for (auto id : map.of_particle)
      ++count[std::size_t(id)];
    const double margin = 2 * column_lattice_spacing(D);
    double sum = 0, sum2 = 0, area = 0, area2 = 0;
    long inside = 0;
    for (std::size_t k = 0; k < map.grains.size(); ++k)
    {
      const Vec3& s = map.grains[k].seed;
      if (s.x() < margin || s.y() < margin || s.x() > size - margin || s.y() > size - margin)
        continue;
      const double d = std::sqrt(4 * count[k] * cell / std::numbers::pi);
      sum += d, sum2 += d * d, area += count[k] * cell, ++inside;
      area2 += std::pow(count[k] * cell, 2);
    }
    const double mean_d = sum / double(inside);
    const double cv = std::sqrt(std::max(0.0, sum2 / double(inside) - mean_d * mean_d)) / mean_d;
    const double mean_area = area / double(inside);
    const double standard_error =
        std::sqrt(std::max(0.0, area2 / double(inside) - mean_area * mean_area) / double(inside));
    const double circle = std::numbers::pi * D * D / 4;
    std::cout << "jitter " << jitter << ": " << inside << " columns inside, mean area / (pi D^2/4) "
              << mean_area / circle << " (standard error " << standard_error / circle
              << "), mean equivalent diameter / D " << mean_d / D << ", CV of the diameters " << cv
              << "\n";
    EXPECT_NEAR(mean_area / circle, 1.0, 3 * standard_error / circle + 0.002)
        << "jitter " << jitter;
  }
}

// A column runs through the whole specimen along its axis: on the simple cubic lattice, the
// particles of one (x, y) share their grain; and a column is where its seed is, whichever
// particles are packed around it (a sub-block gets the same grains as the block).
TEST(ColumnarGrains, ColumnsRunAlongTheAxisAndDependOnPositionOnly)
{
  ParticleStore p;
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 30; ++j)
      for (int i = 0; i < 30; ++i)
        p.add(Vec3(i, j, k) * 2 * radius, radius, 1000);
  const ColumnarGrainsConfig g = columns(10 * radius, 0.5);
  const GrainMap map = assign_grains(p.position, p.radius, g);
  std::map<std::pair<int, int>, int> column_of;
  long mixed = 0;
  for (std::size_t q = 0; q < p.size(); ++q)
  {
    const auto key = std::pair(int(std::lround(p.position[q].x() / radius)),
                               int(std::lround(p.position[q].y() / radius)));
    const auto [it, fresh] = column_of.emplace(key, map.of_particle[q]);
    mixed += !fresh && it->second != map.of_particle[q];
  }
  EXPECT_EQ(mixed, 0);
  EXPECT_GT(map.columns, std::size_t(20));
  std::vector<Vec3> part;
  std::vector<std::size_t> from;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.position[q].x() > 0.02 && p.position[q].y() < 0.04)
      part.push_back(p.position[q]), from.push_back(q);
  const GrainMap sub = assign_grains(part, std::vector<double>(part.size(), radius), g);
  for (std::size_t q = 0; q < part.size(); ++q)
    ASSERT_EQ(sub.grains[std::size_t(sub.of_particle[q])].seed,
              map.grains[std::size_t(map.of_particle[from[q]])].seed);
  // seeded: the same seed gives the same columns, another seed others
  EXPECT_EQ(assign_grains(p.position, p.radius, g).of_particle, map.of_particle);
  ColumnarGrainsConfig other = g;
  other.seed = 8;
  EXPECT_NE(assign_grains(p.position, p.radius, other).of_particle, map.of_particle);
}

// c-axes lie in the plane across the columns: at random (mean of cos 2 theta over the columns
// near 0: 1/sqrt(2 N) is its standard error) or aligned within the given spread (the angles'
// standard deviation within 12 % of it: five standard errors, 1/sqrt(2 N), at the 859
// columns).
TEST(ColumnarGrains, CAxesLieInThePlane)
{
  const auto [x, r] = raster(400, 0.25);
  ColumnarGrainsConfig g = columns(0.01, 0.5);
  g.axis = 2;
  const GrainMap random = assign_grains(x, r, g);
  double c2 = 0;
  for (const auto& grain : random.grains)
  {
    EXPECT_NEAR(grain.c_axis.norm(), 1.0, 1e-15);
    EXPECT_EQ(grain.c_axis.z(), 0.0);
    c2 += std::cos(2 * std::atan2(grain.c_axis.y(), grain.c_axis.x()));
  }
  const double n = double(random.grains.size());
  std::cout << random.grains.size() << " columns: mean cos(2 theta) " << c2 / n << "\n";
  EXPECT_LT(std::abs(c2 / n), 3 / std::sqrt(2 * n));
  g.c_axis_aligned = true;
  g.c_axis_direction = Vec3(1, 1, 5); // its projection: 45 degrees
  g.c_axis_spread = 10;
  const GrainMap aligned = assign_grains(x, r, g);
  double s1 = 0, s2 = 0;
  for (const auto& grain : aligned.grains)
  {
    const double t = std::atan2(grain.c_axis.y(), grain.c_axis.x()) * 180 / std::numbers::pi - 45;
    s1 += t, s2 += t * t;
  }
  const double mean = s1 / n, sd = std::sqrt(s2 / n - mean * mean);
  std::cout << "aligned at 45 degrees, spread 10: mean " << 45 + mean << ", std dev " << sd << "\n";
  EXPECT_NEAR(sd, 10, 1.2);
  EXPECT_NEAR(mean, 0, 3 * 10 / std::sqrt(n));
}

// The granular top layer: particles within its thickness of the top belong to the nearest seed
// of the cubic seed lattice of eq. (2) (brute force), the rest to columns.
TEST(ColumnarGrains, GranularTopLayer)
{
  ParticleStore p;
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i)
        p.add(Vec3(i, j, k) * 2 * radius, radius, 1000);
  ColumnarGrainsConfig g = columns(12 * radius, 0.5);
  g.granular_thickness = 10 * radius;
  g.granular_diameter = 5 * radius;
  const GrainMap map = assign_grains(p.position, p.radius, g);
  const double top = 19 * 2 * radius + radius;
  const double spacing = g.granular_diameter * std::cbrt(std::numbers::pi / 6);
  long wrong = 0, layer = 0;
  for (std::size_t q = 0; q < p.size(); ++q)
  {
    const Grain& grain = map.grains[std::size_t(map.of_particle[q])];
    const bool in_layer = p.position[q].z() > top - g.granular_thickness;
    layer += in_layer;
    EXPECT_EQ(grain.granular, in_layer);
    EXPECT_EQ(std::size_t(map.of_particle[q]) >= map.columns, in_layer);
    if (!in_layer)
      continue;
    double best = 1e300;
    Vec3 nearest;
    const Vec3 node = p.position[q] / spacing;
    for (long k = std::lround(node.z()) - 4; k <= std::lround(node.z()) + 4; ++k)
      for (long j = std::lround(node.y()) - 4; j <= std::lround(node.y()) + 4; ++j)
        for (long i = std::lround(node.x()) - 4; i <= std::lround(node.x()) + 4; ++i)
        {
          const Vec3 s = granular_seed(g, i, j, k);
          if ((s - p.position[q]).squaredNorm() < best)
            best = (s - p.position[q]).squaredNorm(), nearest = s;
        }
    wrong += grain.seed != nearest;
  }
  EXPECT_EQ(layer, 5 * 400); // centres above 39 r - 10 r: the upper 5 layers (z = 30 r .. 38 r)
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(map.grains.size() - map.columns, std::size_t(50));
}

namespace
{
/// A columnar simple cubic block (20 x 20 x 6 particles, columns of 6 diameters) with stiffer,
/// weaker grain boundaries and brittle failure.
CaseConfig columnar_block()
{
  CaseConfig c = cubic_block();
  c.particles.box_size = Vec3(40 * radius, 40 * radius, 12 * radius);
  c.run.static_solver = false;
  c.damage.law.mode = FailureMode::brittle;
  c.damage.tensile_strength = 2e6;
  c.damage.shear_strength = 3e6;
  c.microstructure.grains = columns(12 * radius, 0.5);
  BondClassConfig boundary = BondClassConfig::of_specimen(c.bonds.material, c.damage);
  boundary.material.youngs_modulus = 1e9;
  boundary.material.radius_multiplier = 0.8;
  boundary.tensile_strength = 0.5e6;
  boundary.shear_strength = 0.7e6;
  c.microstructure.grain_boundary = boundary;
  return c;
}
} // namespace

// A bond's class is the grains of its particles, and it carries its class's constants
// (stiffnesses from bond_model.h with the class's material, the class's mean strengths),
// after the spatial renumbering as before it.
TEST(BondClasses, BondsCarryTheirClassConstants)
{
  for (bool spatial : {false, true})
  {
    CaseConfig c = columnar_block();
    c.spatial_order = spatial;
    const Model m = build_model(c);
    const auto& p = m.particles;
    const auto& b = m.bonds;
    ASSERT_EQ(b.bond_class.size(), b.size());
    std::array<long, 3> seen{};
    for (std::size_t k = 0; k < b.size(); ++k)
    {
      const bool boundary = p.grain[std::size_t(b.a[k])] != p.grain[std::size_t(b.b[k])];
      ASSERT_EQ(b.bond_class[k], boundary ? BondClass::grain_boundary : BondClass::intra_grain);
      ++seen[std::size_t(b.bond_class[k])];
      const BondMaterial& mat =
          boundary ? c.microstructure.grain_boundary->material : c.bonds.material;
      const BondStiffness s = bond_stiffness(mat, b.rest_length[k], radius, radius);
      EXPECT_EQ(b.kn[k], s.kn);
      EXPECT_EQ(b.ks[k], s.ks);
      EXPECT_EQ(b.ktor[k], s.ktor);
      EXPECT_EQ(b.kben[k], s.kben);
      EXPECT_EQ(b.radius[k], s.radius);
      EXPECT_EQ(b.tensile_strength[k], boundary ? 0.5e6 : 2e6);
      EXPECT_EQ(b.shear_strength[k], boundary ? 0.7e6 : 3e6);
    }
    std::cout << m.microstructure.columns << " columns, " << seen[0] << " intra-grain and "
              << seen[1] << " grain-boundary bonds\n";
    EXPECT_GT(seen[0], 0);
    EXPECT_GT(seen[1], 0);
    EXPECT_EQ(m.microstructure.bonds_per_class[1], std::size_t(seen[1]));
  }
}

// Scattered strengths: a bond draws around its class's mean with the draw it would have had
// in the homogeneous specimen (the scatter is relative), so classes change the means only.
TEST(BondClasses, ScatterIsRelativeToTheClassMean)
{
  for (auto scatter : {StrengthScatter::normal, StrengthScatter::weibull})
  {
    CaseConfig c = columnar_block();
    c.damage.scatter = scatter;
    c.damage.scatter_deviation = 0.3;
    c.damage.weibull_modulus = 5;
    CaseConfig plain = c;
    plain.microstructure = {};
    const Model m = build_model(c), h = build_model(plain);
    ASSERT_EQ(m.bonds.size(), h.bonds.size());
    for (std::size_t k = 0; k < m.bonds.size(); ++k)
    {
      const bool boundary = m.bonds.bond_class[k] == BondClass::grain_boundary;
      EXPECT_NEAR(m.bonds.tensile_strength[k] / (boundary ? 0.5e6 : 2e6),
                  h.bonds.tensile_strength[k] / 2e6, 1e-14);
      EXPECT_NEAR(m.bonds.shear_strength[k] / (boundary ? 0.7e6 : 3e6),
                  h.bonds.shear_strength[k] / 3e6, 1e-14);
    }
  }
}

namespace
{
/// The InputError message of building @p c ("" when it builds).
std::string error_of(const CaseConfig& c)
{
  try
  {
    build_model(c);
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(MicrostructureInput, RefusedWithOneLine)
{
  auto expect = [](const CaseConfig& c, const std::string& start, const std::string& part)
  {
    const std::string what = error_of(c);
    EXPECT_EQ(what.rfind(start, 0), 0u) << what;
    EXPECT_NE(what.find(part), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  };
  {
    CaseConfig c = columnar_block();
    c.microstructure.grains.diameter = 3 * radius;
    expect(c, "Microstructure/column diameter: ", "below two particle diameters");
    c.microstructure.grains.diameter = 50 * radius;
    expect(c, "Microstructure/column diameter: ", "above the specimen's width");
    c.microstructure.grains.diameter = 12 * radius;
    c.microstructure.grains.granular_thickness = 6 * radius;
    c.microstructure.grains.granular_diameter = 3 * radius;
    expect(c, "Microstructure/granular grain diameter: ", "below two particle diameters");
    c.microstructure.grains.granular_diameter = 6 * radius;
    c.microstructure.grains.granular_thickness = 12 * radius;
    expect(c, "Microstructure/granular layer thickness: ", "leaves no column");
  }
  {
    CaseConfig c = with_weak_planes(3, 0.5);
    c.microstructure.weak_planes->spacing = 1.5 * radius;
    expect(c, "Microstructure/weak plane spacing: ", "below the particle spacing");
    c.microstructure.weak_planes->spacing = 0;
    c.microstructure.weak_planes->offsets = {2 * radius, 3 * radius};
    expect(c, "Microstructure/weak plane offsets: ", "overlap");
    c.microstructure.weak_planes->offsets = {2 * radius, 1.0};
    expect(c, "Microstructure/weak plane offsets: ", "crosses no bond");
    c.microstructure.weak_planes->offsets = {-1.0};
    c.microstructure.weak_planes->spacing = 4 * radius;
    c.microstructure.weak_planes->normal = Vec3::Zero();
    expect(c, "Microstructure/weak plane normal: ", "non-zero");
  }
  {
    CaseConfig c = columnar_block();
    c.microstructure.grain_boundary->tensile_strength = 0;
    expect(c, "Bond class grain_boundary/tensile strength: ", "no strength");
    c = columnar_block();
    c.microstructure.grain_boundary->material.youngs_modulus = -1;
    expect(c, "Bond class grain_boundary/youngs modulus: ", "positive");
  }
}
