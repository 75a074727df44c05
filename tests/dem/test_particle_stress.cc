// Particle and RVE stresses (thesis eq. 54-62, dem/particle_stress.h) and the least-squares
// modulus (eq. 64, dem/measurements.h) against closed-form values.
#include "dem/measurements/measurements.h"
#include "dem/measurements/particle_stress.h"
#include "dem/model/model.h"
#include "dem/solvers/static_solver.h"
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
constexpr double pi = std::numbers::pi;

/// Two touching spheres (r = 5 mm) on x, parallel bond, E_b = 4 GPa.
Model pair_model()
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::row;
  c.particles.count = 2;
  c.particles.radius = 5e-3;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  return build_model(c);
}

/// Simple cubic block, r = 5 mm, PBM: x- face held in x, x+ face pushed by 1e-6 m (static).
Model compressed_cubic_block(Vec3 box)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::cubic;
  c.particles.radius = 5e-3;
  c.particles.box_size = box;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.material.stiffness_ratio = 4.2;
  GroupConfig held{"held", {}, dof_ux, 0, Vec3::Zero()};
  held.selection.kind = GroupSelection::Kind::face;
  held.selection.face_axis = 0;
  GroupConfig pushed = held;
  pushed.name = "pushed";
  pushed.fixed = 0;
  pushed.selection.face_upper = true;
  // every particle: no lateral motion or rotation (a cubic PBM lattice has no lateral coupling)
  GroupConfig all{
      "all", {}, std::uint8_t(dof_uy | dof_uz | dof_rx | dof_ry | dof_rz), 0, Vec3::Zero()};
  all.selection.kind = GroupSelection::Kind::all;
  c.groups = {held, pushed, all};
  LoadConfig push;
  push.group = "pushed";
  push.load.name = "push";
  push.load.kind = LoadKind::displacement;
  c.run.static_solver = true;
  push.load.components = 1;
  push.load.value = Vec3(-1e-6, 0, 0);
  c.loads = {push};
  Model m = build_model(c);
  solve_static(m);
  return m;
}
} // namespace

// Stretch the pair by d: bond force k_n d along x. Particle a (contact at s L_0 = r): sigma_xx =
// r k_n d / V; b likewise; every other component zero. Tension positive. Both theories agree
// for a pure stretch up to the O(d/L) lever-arm change of the current configuration.
TEST(ParticleStress, StretchedPairMatchesClosedForm)
{
  Model m = pair_model();
  const double d = 1e-6, r = 5e-3;
  m.particles.position[1].x() += d;
  const double kn = m.bonds.kn[0];
  const double V = 4.0 / 3.0 * pi * r * r * r, expected = r * kn * d / V;
  for (auto theory : {StressTheory::small_strain, StressTheory::current})
  {
    const ParticleStresses s = particle_stresses(m.particles, m.bonds, theory);
    const double tol = theory == StressTheory::small_strain ? 1e-12 : 2 * d / (2 * r);
    for (int i = 0; i < 2; ++i)
    {
      EXPECT_NEAR(s.sigma[i](0, 0) / expected, 1.0, tol);
      EXPECT_NEAR(s.volume[i], V, 1e-18);
      Tensor3 rest = s.sigma[i];
      rest(0, 0) = 0;
      EXPECT_LT(rest.norm(), 1e-9 * expected);
    }
    EXPECT_NEAR(s.strain_energy, 0.5 * kn * d * d, 1e-12 * kn * d * d);
  }
}

// A pure rigid rotation stores nothing: no stress in either theory.
TEST(ParticleStress, RigidRotationIsStressFree)
{
  Model m = pair_model();
  const Quat q(Eigen::AngleAxisd(1e-4, Vec3(0.3, -0.5, 0.8).normalized()));
  for (std::size_t i = 0; i < 2; ++i)
  {
    m.particles.position[i] = q * m.particles.reference_position[i];
    m.particles.orientation[i] = q;
  }
  const double scale = m.bonds.kn[0] * 1e-6 / 5e-7; // a 1 um stretch's stress, for scale
  for (auto theory : {StressTheory::small_strain, StressTheory::current})
  {
    const ParticleStresses s = particle_stresses(m.particles, m.bonds, theory);
    // small_strain: rotation enters at second order (1e-8 of a unit strain)
    EXPECT_LT(s.sigma[0].norm(), 1e-6 * scale);
  }
}

// Cubic block under uniaxial compression (static solve): every particle chain carries F/N_chains;
// the RVE average over the gauge volume equals F/A to round-off, and slabs holding one lattice
// layer each give F/A inside and F/(2A) at the two ends (end particles have one bond).
TEST(RveStress, CubicBlockLayersAndAverage)
{
  const Vec3 box(0.08, 0.04, 0.03);
  Model m = compressed_cubic_block(box);
  const auto& p = m.particles;
  const Group& pushed = m.groups[1];
  const double force = total_force(p, pushed).x(); // reaction on the pushed end
  const double area = box.y() * box.z(), sigma_b = -std::abs(force) / area;
  ASSERT_GT(std::abs(force), 0);
  const ParticleStresses s = particle_stresses(p, m.bonds);
  const auto [lo, hi] = reference_extent(p);
  const double gauge = box.x() - 2 * 5e-3;
  const Tensor3 rve = rve_average(p, s, lo, hi, area * gauge);
  EXPECT_NEAR(rve(0, 0) / sigma_b, 1.0, 1e-12);
  EXPECT_LT((rve - rve.transpose()).norm(), 1e-9 * std::abs(sigma_b));
  const int layers = 8;
  const StressLayers l = stress_layers(p, s, lo, hi, 0, layers);
  ASSERT_EQ(int(l.sigma.size()), layers);
  for (int j = 0; j < layers; ++j)
  {
    EXPECT_EQ(l.count[j], 4 * 3);
    const double expected = (j == 0 || j == layers - 1) ? 0.5 : 1.0;
    EXPECT_NEAR(l.sigma[j](0, 0) / sigma_b, expected, 1e-9) << "slab " << j; // CG tolerance
  }
  // histogram of sigma_xx / mean: interior particles at 8/7, end particles at 4/7 of the mean
  const StressHistogram h = stress_histogram(s, 0, 20);
  long total = 0;
  for (long c : h.counts)
    total += c;
  EXPECT_EQ(total, long(p.size()));
  EXPECT_NEAR(h.max_ratio, 8.0 / 7.0, 1e-9);
}

// Eq. 64 by least squares: a straight force-displacement line with an offset and an early
// transient gives the line's slope; E = slope * gauge / area.
TEST(ModulusFit, RecoversTheSlopeOfTheCurve)
{
  AxialResponse geometry;
  geometry.gauge_length = 0.24, geometry.area = 0.01;
  std::vector<double> du, force;
  const double slope = 1.3e8, offset = 40;
  for (int k = 0; k <= 100; ++k)
  {
    const double u = -1e-6 * k;
    du.push_back(u);
    force.push_back(slope * u + offset + (k < 20 ? 1e3 * std::sin(k) : 0.0)); // transient
  }
  const ModulusFit fit = fit_youngs_modulus(du, force, geometry);
  EXPECT_EQ(fit.points, 76); // |du| >= 25 % of the largest
  EXPECT_NEAR(fit.youngs_modulus / (slope * 0.24 / 0.01), 1.0, 1e-12);
  EXPECT_EQ(fit_youngs_modulus({0.0}, {1.0}, geometry).points, 0);
}
