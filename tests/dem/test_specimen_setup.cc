// Specimen set-up (thesis section 4.1): porosity of the packing box and the density scaling of
// eq. 63, rho_p = rho / (1 - porosity), which gives the specimen the continuum's mass.
#include "dem/model/model.h"
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
CaseConfig cubic_specimen(bool scale)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::cubic;
  c.particles.radius = 0.0125;
  c.particles.box_size = Vec3(0.25, 0.1, 0.1);
  c.particles.density = 910; // sea ice
  c.particles.scale_density_by_porosity = scale;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  return c;
}

double total_mass(const Model& m)
{
  double sum = 0;
  for (double x : m.particles.mass)
    sum += x;
  return sum;
}
} // namespace

// A simple cubic lattice filling its box has porosity 1 - pi/6 exactly; without scaling the
// specimen weighs (pi/6) rho V, with eq. 63 exactly rho V (1e-12: round-off).
TEST(SpecimenSetup, CubicPorosityAndEq63)
{
  const double V = 0.25 * 0.1 * 0.1, rho = 910;
  const Model plain = build_model(cubic_specimen(false));
  EXPECT_NEAR(plain.porosity, 1 - std::numbers::pi / 6, 1e-12);
  EXPECT_NEAR(plain.packing_volume, V, 1e-15);
  EXPECT_NEAR(total_mass(plain) / (std::numbers::pi / 6 * rho * V), 1.0, 1e-12);
  const Model scaled = build_model(cubic_specimen(true));
  EXPECT_NEAR(total_mass(scaled) / (rho * V), 1.0, 1e-12);
  // heavier particles, same stiffness: the critical step grows by 1/sqrt(1 - p)
  EXPECT_NEAR(scaled.critical.critical() / plain.critical.critical(),
              1 / std::sqrt(std::numbers::pi / 6), 1e-9);
}

// HCP fills a box less perfectly than the ideal lattice (porosity 0.2595) because of the
// planar walls (thesis section 4.1, Table 2); the porosity approaches the ideal as r falls.
// Lattice porosity is taken over the lattice's extent, as in Table 2 (r = 5 mm: 0.32, given to
// two digits, so +-0.005).
TEST(SpecimenSetup, HcpPorosityApproachesTheIdealLattice)
{
  const double ideal = 1 - std::numbers::pi / (3 * std::sqrt(2.0));
  double previous = 1;
  for (double r : {0.0125, 0.0075, 0.005})
  {
    CaseConfig c = cubic_specimen(false);
    c.particles.kind = ParticleSource::Kind::hcp;
    c.particles.radius = r;
    const Model m = build_model(c);
    std::cout << "HCP r = " << r << " m: porosity " << m.porosity << " (ideal " << ideal << ")\n";
    EXPECT_GT(m.porosity, ideal);
    EXPECT_LT(m.porosity, previous);
    previous = m.porosity;
    if (r == 0.005)
    {
      EXPECT_NEAR(m.porosity, 0.32, 0.005);
    }
  }
}

// FCC = triangular layers stacked ABC: every particle of layer 3 sits exactly above one of
// layer 0, none of layers 1 and 2 does (HCP: layer 2 does); interior spheres touch 12
// neighbours, like HCP and unlike the simple cubic lattice's 6.
TEST(SpecimenSetup, FccStackingAndCoordination)
{
  for (auto kind : {ParticleSource::Kind::fcc, ParticleSource::Kind::hcp})
  {
    CaseConfig c = cubic_specimen(false);
    c.particles.kind = kind;
    c.particles.radius = 0.005;
    c.particles.box_size = Vec3(0.06, 0.06, 0.05);
    const Model m = build_model(c);
    const auto& p = m.particles;
    const double r = 0.005, dz = 2 * r * std::sqrt(2.0 / 3.0);
    auto layer_xy = [&](int k)
    {
      std::vector<Vec3> xy;
      for (std::size_t i = 0; i < p.size(); ++i)
        if (std::abs(p.position[i].z() - (r + k * dz)) < 1e-9)
          xy.push_back(Vec3(p.position[i].x(), p.position[i].y(), 0));
      return xy;
    };
    auto stacked = [&](int k) // some particle of layer k sits above one of layer 0
    {
      for (const auto& a : layer_xy(k))
        for (const auto& b : layer_xy(0))
          if ((a - b).norm() < 1e-9)
            return true;
      return false;
    };
    ASSERT_FALSE(layer_xy(3).empty());
    EXPECT_FALSE(stacked(1));
    EXPECT_EQ(stacked(2), kind == ParticleSource::Kind::hcp);
    EXPECT_EQ(stacked(3), kind == ParticleSource::Kind::fcc);
    const int most = *std::max_element(p.coordination.begin(), p.coordination.end());
    EXPECT_EQ(most, 12);
  }
}
