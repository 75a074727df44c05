// The figures behind the warnings and refusals of results that would look complete when they are
// not (app/output/result_warnings.h), on configurations whose answers are known by construction:
//  - bond_coverage (dem/model/bond_coverage.h): the multiplier that bonds the closest pair and
//    the one that bonds every particle to its nearest neighbour, |x_a - x_b| / (R_a + R_b);
//  - largest_rotation (dem/measurements/measurements.h): of a particle and of a bond's axis;
//  - fit_flexural_modulus: eq. 69 with the slope through the origin of a straight load curve.
#include "dem/bonds/bonding.h"
#include "dem/measurements/measurements.h"
#include "dem/model/bond_coverage.h"
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace dem = dembridge::dem;

namespace
{
dem::ParticleStore row(const std::vector<double>& x, double radius)
{
  dem::ParticleStore p;
  for (double xi : x)
    p.add(dem::Vec3(xi, 0, 0), radius, 1000);
  return p;
}
} // namespace

// Spheres of radius 1 at x = 0, 2.1 and 6: the pairs' ratios are 1.05 (0-1), 1.95 (1-2) and 3
// (0-2, beyond the search distance of 4 radii); nearest per particle 1.05, 1.05, 1.95.
TEST(BondCoverage, MultipliersOfTheClosestPairAndOfEveryParticle)
{
  const dem::ParticleStore p = row({0, 2.1, 6}, 1.0);
  const dem::BondCoverage c = dem::bond_coverage(p);
  EXPECT_EQ(c.unbonded, 3);
  EXPECT_NEAR(c.closest_pair_multiplier, 1.05, 1e-12);
  EXPECT_NEAR(c.every_particle_multiplier, 1.95, 1e-12);
}

// Bonding with the multiplier bond_coverage names bonds every particle (the formation rule's own
// tolerance, 1e-9, covers the division's roundoff); just below it, the last particle stays loose.
TEST(BondCoverage, TheNamedMultiplierBondsEveryParticle)
{
  dem::BondMaterial mat;
  mat.youngs_modulus = 1e9;
  for (const double factor : {1.0, 0.999})
  {
    dem::ParticleStore p = row({0, 2.1, 6, 8.3}, 1.0);
    const double every = dem::bond_coverage(p).every_particle_multiplier;
    dem::BondStore b;
    dem::form_bonds(p, b, mat, factor * every);
    EXPECT_EQ(dem::bond_coverage(p).unbonded, factor == 1.0 ? 0 : 2) << factor;
  }
}

// A particle with no neighbour within the search distance: no finite multiplier bonds it.
TEST(BondCoverage, AnIsolatedParticleHasNoMultiplier)
{
  const dem::BondCoverage c = dem::bond_coverage(row({0, 2.1, 30}, 1.0));
  EXPECT_NEAR(c.closest_pair_multiplier, 1.05, 1e-12);
  EXPECT_EQ(c.every_particle_multiplier, 0.0);
}

// Two bonded spheres: one turned by 0.3 rad about z; then the other moved so that the bond's
// axis turns by 0.2 rad while the particles turn by 0.1 rad.
TEST(LargestRotation, OfParticlesAndOfBondAxes)
{
  dem::ParticleStore p = row({0, 2}, 1.0);
  dem::BondMaterial mat;
  mat.youngs_modulus = 1e9;
  dem::BondStore b;
  dem::form_bonds(p, b, mat, 1.0);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(dem::largest_rotation(p, b), 0.0);
  p.orientation[1] = dem::Quat(Eigen::AngleAxisd(0.3, dem::Vec3::UnitZ()));
  EXPECT_NEAR(dem::largest_rotation(p, b), 0.3, 1e-12);
  p.orientation[1] = dem::Quat(Eigen::AngleAxisd(-0.1, dem::Vec3::UnitY()));
  p.position[1] = dem::Vec3(2 * std::cos(0.2), 2 * std::sin(0.2), 0);
  EXPECT_NEAR(dem::largest_rotation(p, b), 0.2, 1e-12);
}

// A straight load curve F = k delta: E_f = k / 2 times the compliance factor, whatever the
// sampling; one record is no curve.
TEST(FlexuralFit, SlopeThroughTheOriginTimesTheComplianceFactor)
{
  dem::FlexuralResponse geometry;
  geometry.compliance_factor = 150.0; // 1/m^2
  std::vector<double> deflection, load;
  for (int k = 0; k <= 40; ++k)
  {
    deflection.push_back(2.5e-6 * k);
    load.push_back(-2e7 * 2.5e-6 * k); // the supports' reaction: either sign
  }
  const dem::ModulusFit fit = dem::fit_flexural_modulus(deflection, load, geometry);
  EXPECT_EQ(fit.points, 40);
  EXPECT_NEAR(fit.youngs_modulus, 2e7 / 2 * 150.0, 1e-6 * 1.5e9);
  const dem::ModulusFit none = dem::fit_flexural_modulus({0, 1e-6}, {0, 20}, geometry);
  EXPECT_EQ(none.points, 1);
  EXPECT_EQ(none.youngs_modulus, 0.0);
}
