// A columnar specimen's own stiffness tensor (dem/measurements/elasticity_tensor.h) is
// transversely isotropic about the column axis: columns with random shapes, their boundaries
// facing every direction of the plane, make the plane isotropic on average (six seeds), each
// specimen within a stated spread, and the grain boundaries soften the specimen across the
// columns more than along them.
// The packing is the HCP lattice stacked along z, itself transversely isotropic about z
// (hexagonal symmetry; its finite block within 0.21 % of C11, test_elasticity_tensor), so what
// breaks the in-plane isotropy is the columns' finite number.
#include "dem/measurements/elasticity_tensor.h"
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <numbers>

using namespace dembridge::dem;

namespace
{
constexpr double radius = 2.5e-3;

/// The thesis' PBM on an HCP block 0.1 x 0.1 x 0.03 m of r = 2.5 mm; with @p columns, columns of
/// 12.5 mm along z (2.5 particle diameters; about 80 in the specimen) whose boundary bonds have
/// a quarter of the bonds' Young's modulus.
CaseConfig block(bool columns, unsigned long seed)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::hcp;
  c.particles.radius = radius;
  c.particles.box_size = Vec3(0.1, 0.1, 0.03);
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.material.stiffness_ratio = 4.2;
  c.run.static_solver = true;
  if (columns)
  {
    auto& g = c.microstructure.grains;
    g.enabled = true;
    g.diameter = 12.5e-3;
    g.jitter = 0.5;
    g.seed = seed;
    BondClassConfig boundary = BondClassConfig::of_specimen(c.bonds.material, c.damage);
    boundary.material.youngs_modulus = 1e9;
    c.microstructure.grain_boundary = boundary;
  }
  return c;
}

/// In-plane deviations from transverse isotropy about z: the spread (max - min) / mean of the
/// Young's modulus E(theta) over the directions of the x-y plane, |C44 - C55| / mean and
/// |C66 - (C11 - C12)/2| / C66.
struct InPlaneSpread
{
  double youngs, shear_out, shear_in;
};

InPlaneSpread in_plane_spread(const Matrix6& C)
{
  const Matrix6 S = C.inverse();
  // E(theta) = 1 / (v . S v), v = (n_x^2, n_y^2, 0, 0, 0, n_x n_y): the Voigt stress of a unit
  // uniaxial stress along n = (cos theta, sin theta, 0)
  double lo = 1e300, hi = 0, sum = 0;
  const int steps = 36;
  for (int k = 0; k < steps; ++k)
  {
    const double t = std::numbers::pi * k / steps, c = std::cos(t), s = std::sin(t);
    Vector6 v;
    v << c * c, s * s, 0, 0, 0, c * s;
    const double E = 1.0 / v.dot(S * v);
    lo = std::min(lo, E), hi = std::max(hi, E), sum += E;
  }
  return {(hi - lo) / (sum / steps), 2 * std::abs(C(3, 3) - C(4, 4)) / (C(3, 3) + C(4, 4)),
          std::abs(C(5, 5) - 0.5 * (C(0, 0) - C(0, 1))) / C(5, 5)};
}

std::pair<Matrix6, std::size_t> measure(bool columns, unsigned long seed)
{
  const Model m = build_model(block(columns, seed));
  ElasticityMeasurementSettings s;
  s.core_period = lattice_axis_periods(ParticleSource::Kind::hcp, radius);
  return {measured_stiffness_tensor(m, s).properties.stiffness, m.microstructure.columns};
}
} // namespace

TEST(ColumnarElasticity, TransverselyIsotropicAboutTheColumns)
{
  const Matrix6 plain = measure(false, 0).first;
  const InPlaneSpread p = in_plane_spread(plain);
  std::cout << "HCP block: C11 " << plain(0, 0) / 1e9 << " C22 " << plain(1, 1) / 1e9 << " C33 "
            << plain(2, 2) / 1e9 << " GPa; in-plane spreads: E " << p.youngs << ", C44/C55 "
            << p.shear_out << ", C66 " << p.shear_in << "\n";
  Matrix6 mean = Matrix6::Zero();
  const int seeds = 6;
  double worst = 0;
  for (int seed = 1; seed <= seeds; ++seed)
  {
    const auto [C, columns] = measure(true, seed);
    mean += C / seeds;
    const InPlaneSpread d = in_plane_spread(C);
    worst = std::max({worst, d.youngs, d.shear_out, d.shear_in});
    std::cout << "seed " << seed << ": " << columns << " columns; C11 " << C(0, 0) / 1e9 << " C22 "
              << C(1, 1) / 1e9 << " C33 " << C(2, 2) / 1e9 << " GPa; in-plane spreads: E "
              << d.youngs << ", C44/C55 " << d.shear_out << ", C66 " << d.shear_in << "\n";
    EXPECT_GE(columns, std::size_t(50));
  }
  const InPlaneSpread m = in_plane_spread(mean);
  std::cout << "mean of " << seeds << " seeds: C11 " << mean(0, 0) / 1e9 << " C22 "
            << mean(1, 1) / 1e9 << " C33 " << mean(2, 2) / 1e9 << " GPa; in-plane spreads: E "
            << m.youngs << ", C44/C55 " << m.shear_out << ", C66 " << m.shear_in
            << "; C11/C11_plain " << mean(0, 0) / plain(0, 0) << ", C33/C33_plain "
            << mean(2, 2) / plain(2, 2) << "\n";
  // One specimen (about 90 columns; the measured core holds the area of 52): the in-plane
  // constants agree within 8 % (measured over the six seeds: at most 5.9 %, E at seed 1).
  EXPECT_LT(worst, 0.08);
  // On average over the seeds the columns add no in-plane anisotropy of their own: the mean
  // tensor's spreads are within 1.5 times the homogeneous HCP block's (the trace of its held
  // boundary, 0.9 %, 0.36 %, 0.97 %; measured 0.84 %, 0.19 %, 0.88 %).
  EXPECT_LT(m.youngs, 1.5 * p.youngs);
  EXPECT_LT(m.shear_out, 1.5 * p.shear_out);
  EXPECT_LT(m.shear_in, 1.5 * p.shear_in);
  // Softer boundaries soften the specimen across the columns more than along them (measured:
  // C11 to 0.45 of the block's, C33 to 0.74).
  EXPECT_GT(mean(2, 2) / plain(2, 2), mean(0, 0) / plain(0, 0) + 0.1);
}
