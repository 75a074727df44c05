// Strength scatter keyed by position (Damage/scatter key = position, bond_strength.h): a bond's
// strengths depend on where it is, not on the order the bonds were formed in.
//  - The lattice of a small box and the same lattice in a box three times longer, shifted by
//    whole periods (a coupled run's particle region and its full DEM, `dembridge compare`):
//    every bond of the small one has, in the large one, a bond at the same midpoint with
//    bit-identical strengths. Keyed by bond order they differ.
//  - The draws are still the distribution asked for: over the 8,300 bonds of the large
//    lattice the normal scatter's mean lies within 4 standard errors of the given strength and
//    its relative standard deviation within 3 % of delta = 0.2 (4 standard errors; truncation
//    at zero is a 5-sigma event here); neighbouring bonds are uncorrelated (|r| < 0.05).
#include "dem/model/model.h"
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <tuple>

using namespace dembridge::dem;

namespace
{
CaseConfig lattice(double origin_x, double length, bool by_position)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::cubic;
  c.particles.radius = 0.005;
  c.particles.origin = Vec3(origin_x, 0, 0);
  c.particles.box_size = Vec3(length, 0.1, 0.1);
  c.particles.density = 925;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.damage.law.mode = FailureMode::brittle;
  c.damage.tensile_strength = 1e6;
  c.damage.shear_strength = 2e6;
  c.damage.scatter = StrengthScatter::normal;
  c.damage.scatter_deviation = 0.2;
  c.damage.seed = 7;
  c.damage.scatter_by_position = by_position;
  return c;
}

using Key = std::tuple<long, long, long>;
std::map<Key, std::pair<double, double>> strengths_by_midpoint(const Model& m)
{
  std::map<Key, std::pair<double, double>> out;
  for (std::size_t k = 0; k < m.bonds.size(); ++k)
  {
    const Vec3 mid = 0.5 * (m.particles.reference_position[m.bonds.a[k]] +
                            m.particles.reference_position[m.bonds.b[k]]);
    out[{std::lround(mid.x() * 1e6), std::lround(mid.y() * 1e6), std::lround(mid.z() * 1e6)}] = {
        m.bonds.tensile_strength[k], m.bonds.shear_strength[k]};
  }
  return out;
}

/// Bonds of the small lattice whose strengths the large one reproduces exactly.
std::size_t same_strengths(bool by_position, std::size_t* n_small)
{
  const Model small = build_model(lattice(0.1, 0.1, by_position));
  const Model large = build_model(lattice(0.0, 0.3, by_position)); // 0.1 m = 10 periods lower
  const auto a = strengths_by_midpoint(small), b = strengths_by_midpoint(large);
  std::size_t same = 0;
  for (const auto& [key, s] : a)
  {
    const auto it = b.find(key);
    same += it != b.end() && it->second == s;
  }
  *n_small = a.size();
  return same;
}
} // namespace

TEST(StrengthScatter, PositionKeyGivesTheSameBondTheSameStrengths)
{
  std::size_t n = 0;
  EXPECT_EQ(same_strengths(true, &n), n);
  EXPECT_GT(n, 2000u);
  std::size_t n_order = 0;
  const std::size_t same_order = same_strengths(false, &n_order);
  EXPECT_GT(n_order, 2000u);
  EXPECT_LT(same_order, n_order / 10); // in bond order: different draws
}

TEST(StrengthScatter, PositionKeyedDrawsFollowTheDistribution)
{
  const Model m = build_model(lattice(0.0, 0.3, true));
  const auto& s = m.bonds.tensile_strength;
  const double n = double(s.size());
  double mean = 0, var = 0, cov = 0;
  for (double x : s)
    mean += x / n;
  for (std::size_t k = 0; k < s.size(); ++k)
  {
    var += (s[k] - mean) * (s[k] - mean) / n;
    if (k + 1 < s.size())
      cov += (s[k] - mean) * (s[k + 1] - mean) / n;
  }
  const double sd = std::sqrt(var);
  std::cout << s.size() << " bonds: mean " << mean << " Pa, relative sd " << sd / 1e6
            << ", lag-1 correlation " << cov / var << "\n";
  EXPECT_LT(std::abs(mean - 1e6), 4 * 0.2e6 / std::sqrt(n));
  EXPECT_NEAR(sd / 1e6, 0.2, 0.2 * 0.03);
  EXPECT_LT(std::abs(cov / var), 0.05);
}
