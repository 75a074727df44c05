// Basal bonds (dem/microstructure/microstructure.h) as smooth joints whose normal is their
// grain's c-axis (dem/bonds/smooth_joint.h), against the joint's closed form on a random
// packing of columns, each grain with its own c-axis. Under a uniform displacement gradient G
// (no rotations) a bond whose particles sit at x_a, x_b has the relative displacement
// Delta = G (x_b - x_a) at its contact point (to first order in G), and its contact force on b is
//   basal joint (normal c):  F = -(k_n (Delta . c) c + k_s (Delta - (Delta . c) c))
//   any other bond (axis e_0): F = -(k_n (Delta . e_0) e_0 + k_s (Delta - (Delta . e_0) e_0))
// so a basal joint shears by the slip along its grain's basal plane whatever its own axis:
//   - a strain along c alone (G = -eps c c^T) gives Delta = -eps L (e_0 . c) c: no basal joint
//     shears, where a plain bond at angle theta to c shears by eps L cos(theta) sin(theta);
//   - a slip along the basal plane (G = gamma s c^T, s normal to c) gives every basal joint the
//     shear force k_s gamma L (e_0 . c) along s: k_s times the slip across the distance
//     L (e_0 . c) between its particles' basal planes, and no normal force.
#include "dem/measurements/particle_stress.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <numbers>
#include <numeric>
#include <set>

using namespace dembridge::dem;

namespace
{
constexpr double deg = std::numbers::pi / 180;

/// A random packing of r = 2.5 mm spheres, 0.06 x 0.06 x 0.03 m, 20 mm columns along z,
/// parallel bonds (k_n = 4.2 k_s, so the split's two parts differ), basal bonds within 40
/// degrees of their grain's c-axis; c-axes random in the plane, or all along @p aligned.
Model columns(bool smooth, const Vec3* aligned)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::random;
  c.particles.radius = 2.5e-3;
  c.particles.box_size = Vec3(0.06, 0.06, 0.03);
  c.particles.seed = 2;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.material.stiffness_ratio = 4.2;
  c.bonds.contact_radius_multiplier = 1.04;
  c.microstructure.grains.enabled = true;
  c.microstructure.grains.axis = 2;
  c.microstructure.grains.diameter = 0.02;
  c.microstructure.grains.seed = 5;
  if (aligned)
    c.microstructure.grains.c_axis_aligned = true,
    c.microstructure.grains.c_axis_direction = *aligned;
  c.microstructure.basal_cone = 40;
  c.microstructure.basal_smooth_joint = smooth;
  return build_model(c);
}

/// The bonds' contact forces (explicit solver, every particle held) with every particle moved by
/// G x from its reference position, no rotations.
void deform_and_evaluate(Model& m, const Eigen::Matrix3d& G)
{
  ParticleStore& p = m.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    p.position[i] = p.reference_position[i] + G * p.reference_position[i];
  std::vector<int> all(p.size());
  std::iota(all.begin(), all.end(), 0);
  ExplicitSolver solver(p, m.bonds, {{"all", all}}, {{0, 63}}, {}, {1e-7, 0.0, 1});
  solver.step(true);
}

Vec3 split(const Vec3& delta, const Vec3& n, double kn, double ks)
{
  const double dn = delta.dot(n);
  return -(kn * dn * n + ks * (delta - dn * n));
}

/// The grain's c-axis of bond k.
Vec3 c_axis_of(const Model& m, std::size_t k)
{
  return m.microstructure.grains[std::size_t(m.particles.grain[std::size_t(m.bonds.a[k])])].c_axis;
}

Vec3 separation(const Model& m, std::size_t k)
{
  const auto& x = m.particles.reference_position;
  return x[std::size_t(m.bonds.b[k])] - x[std::size_t(m.bonds.a[k])];
}
} // namespace

// A generic gradient on random c-axes: every basal bond splits against its own grain's c-axis
// (the block loop gathers a normal per bond), every other bond against its axis, to the
// closed form's first order (1e-5 at |G| ~ 1e-6); the solver's SIMD loop gives what the scalar
// kernel gives (1e-9).
TEST(BasalJoint, EachBasalBondSplitsAgainstItsGrainsCAxis)
{
  Model m = columns(true, nullptr);
  Eigen::Matrix3d G;
  G << 0.7, -0.4, 1.1, 0.3, -0.9, 0.5, -0.6, 0.2, 0.8;
  G *= 1e-6; // the closed form's second order ~1e-6; the loops' round-off below 1e-9 of F
  deform_and_evaluate(m, G);
  const BondStore& b = m.bonds;
  double worst_basal = 0, worst_other = 0, worst_kernel = 0, widest = 0;
  long basal = 0;
  std::set<std::int32_t> grains;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const Vec3 delta = G * separation(m, k);
    const bool is_basal = b.bond_class[k] == BondClass::basal;
    const Vec3 n = is_basal ? c_axis_of(m, k) : Vec3(b.rest_axis[k]);
    const Vec3 expected = split(delta, n, b.kn[k], b.ks[k]);
    const double error = (b.force[k] - expected).norm() / expected.norm();
    (is_basal ? worst_basal : worst_other) = std::max(is_basal ? worst_basal : worst_other, error);
    const BondContactForce s = bond_contact_force(m.particles, b, k);
    worst_kernel = std::max(worst_kernel, (s.force - b.force[k]).norm() / expected.norm());
    if (is_basal)
    {
      ++basal, grains.insert(m.particles.grain[std::size_t(b.a[k])]);
      widest = std::max(widest, std::acos(std::abs(b.rest_axis[k].dot(n))) / deg);
    }
  }
  std::cout << basal << " basal bonds in " << grains.size() << " grains of "
            << m.microstructure.columns << " (axes up to " << widest
            << " deg from c): largest error " << worst_basal << " (basal), " << worst_other
            << " (others); solver vs kernel " << worst_kernel << "\n";
  EXPECT_GT(basal, 200);
  EXPECT_GT(grains.size(), 8u);
  EXPECT_GT(widest, 30.0); // axes across the cone: the split is not along the bond
  EXPECT_LT(worst_basal, 1e-5);
  EXPECT_LT(worst_other, 1e-5);
  EXPECT_LT(worst_kernel, 1e-9);
}

// c-axes along x: a strain along c shears no basal joint (plain basal bonds do, by their
// axes' closed form); a slip along the basal plane gives every basal joint k_s gamma L (e_0 . c)
// along it, no normal force.
TEST(BasalJoint, StrainAlongCShearsNoBasalPlaneAndSlipShearsThemAll)
{
  const Vec3 c = Vec3::UnitX(), s = Vec3::UnitZ();
  const double eps = 1e-8, gamma = 1e-8;
  Model joint = columns(true, &c), plain = columns(false, &c);
  deform_and_evaluate(joint, -eps * c * c.transpose());
  deform_and_evaluate(plain, -eps * c * c.transpose());
  double joint_shear = 0, plain_error = 0, plain_shear = 0;
  long basal = 0;
  for (std::size_t k = 0; k < joint.bonds.size(); ++k)
  {
    if (joint.bonds.bond_class[k] != BondClass::basal)
      continue;
    ++basal;
    const Vec3 F = joint.bonds.force[k], Fp = plain.bonds.force[k];
    joint_shear = std::max(joint_shear, (F - F.dot(c) * c).norm() / F.norm());
    const Vec3 e = plain.bonds.rest_axis[k];
    const Vec3 expected =
        split(-eps * separation(plain, k).dot(c) * c, e, plain.bonds.kn[k], plain.bonds.ks[k]);
    plain_error = std::max(plain_error, (Fp - expected).norm() / expected.norm());
    plain_shear = std::max(plain_shear, (Fp - Fp.dot(c) * c).norm() / Fp.norm());
  }
  std::cout << basal << " basal bonds; strain along c: largest shear / force " << joint_shear
            << " (joints), " << plain_shear << " (plain bonds, their closed form to " << plain_error
            << ")\n";
  EXPECT_GT(basal, 200);
  EXPECT_LT(joint_shear, 1e-6);
  EXPECT_GT(plain_shear, 0.2);
  EXPECT_LT(plain_error, 1e-6);

  Model slipped = columns(true, &c);
  deform_and_evaluate(slipped, gamma * s * c.transpose());
  double worst = 0;
  for (std::size_t k = 0; k < slipped.bonds.size(); ++k)
  {
    if (slipped.bonds.bond_class[k] != BondClass::basal)
      continue;
    const double across = separation(slipped, k).dot(c); // L (e_0 . c)
    const Vec3 expected = -slipped.bonds.ks[k] * gamma * across * s;
    worst = std::max(worst, (slipped.bonds.force[k] - expected).norm() / expected.norm());
  }
  std::cout << "slip along the basal plane: largest error against k_s gamma L (e_0 . c) " << worst
            << "\n";
  EXPECT_LT(worst, 1e-6);
}
