// The smooth joint (dem/bonds/smooth_joint.h) against its closed forms:
//  - one bond: the contact force is the projection of the displacement on the joint's normal
//    and plane, F_c = k_n D_n n + k_s D_s (eq. 1-2), whatever the bond's own axis, carries no
//    couple (eq. 3), and is objective (eq. 5);
//  - a one-plane specimen sheared along its plane, the two blocks rigid (every particle's motion
//    prescribed, so the joint alone deforms): on the simple cubic lattice every bond the plane
//    crosses is alike, and with smooth joints each carries k_s u of a slip u along the plane, so
//    the joint's shear stiffness per crossing bond is k_s and its peak shear force per bond
//    tau_c A, for any tilt theta of the plane against the lattice. A bond along the lattice
//    axis a at angle alpha to the slip carries instead (k_n cos^2 alpha + k_s sin^2 alpha) u, and
//    fails on the normal force its axis takes: the plain bonds' joint is stiffer as the plane
//    tilts, and its peak another.
#include "dem/bonds/bond_kernel.h"
#include "dem/bonds/bond_matrix.h"
#include "dem/measurements/particle_stress.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/static_solver.h"
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <numbers>
#include <numeric>

using namespace dembridge::dem;

namespace
{
constexpr double deg = std::numbers::pi / 180;

/// A bond of length 2 mm along e0 with kn != ks (the split must tell them apart).
BondConstants pair_constants(const Vec3& e0)
{
  return {2e-3, e0, 3e6, 1e6, 0.4, 0.7, 0.5, 0.0, 0.0};
}

BondKinematics at_rest(const BondConstants& c)
{
  BondKinematics k;
  k.xa = Vec3(0.1, -0.2, 0.05), k.xb = k.xa + c.L0 * c.e0;
  k.qa = k.qb = Quat::Identity();
  k.va = k.vb = k.wa = k.wb = Vec3::Zero();
  return k;
}
} // namespace

// eq. (1)-(3): a small displacement u of b (no rotation) gives D = -u to first order, so
// F_c = -(k_n (u.n) n + k_s (u - (u.n) n)) and M_c = 0, for a bond at 40 degrees to the normal.
TEST(SmoothJoint, OneBondSplitsAgainstThePlaneNormal)
{
  const Vec3 N = Vec3(1, 2, -0.5).normalized();
  const Vec3 e0 = Eigen::AngleAxisd(40 * deg, Vec3(0.3, -1, 2).cross(N).normalized()) * N;
  const BondConstants c = pair_constants(e0);
  BondKinematics k = at_rest(c);
  const Vec3 u = 1e-9 * Vec3(0.7, -0.4, 1.1);
  k.xb += u;
  const BondResult joint = evaluate_bond<false>(k, c, &N);
  const Vec3 expected = -(c.kn * u.dot(N) * N + c.ks * (u - u.dot(N) * N));
  EXPECT_LT((joint.Fc - expected).norm(), 1e-6 * expected.norm()) << joint.Fc.transpose();
  EXPECT_EQ(joint.Mc.norm(), 0.0);
  // the plane's normal with either sign is the same joint (eq. 5 signs it by e0)
  const Vec3 flipped = -N;
  EXPECT_LT((evaluate_bond<false>(k, c, &flipped).Fc - joint.Fc).norm(), 1e-12 * expected.norm());
  // the unified law splits against its own axis: another force
  const BondResult plain = evaluate_bond<false>(k, c);
  const Vec3 along_axis = -(c.kn * u.dot(e0) * e0 + c.ks * (u - u.dot(e0) * e0));
  EXPECT_LT((plain.Fc - along_axis).norm(), 1e-6 * expected.norm());
  EXPECT_GT((plain.Fc - joint.Fc).norm(), 0.1 * expected.norm());
  // energy, eq. (4): U = (kn D_n^2 + ks |D_s|^2) / 2 with D = -u
  const double un = u.dot(N), us2 = (u - un * N).squaredNorm();
  EXPECT_NEAR(joint.strain_energy, 0.5 * (c.kn * un * un + c.ks * us2), 1e-6 * joint.strain_energy);
  // the linearised joint (the static solver's matrix) gives the same force on b
  const Eigen::Matrix3d R = bond_frame(e0);
  const Vec3 local_normal = R.transpose() * N;
  BondStiffness s;
  s.kn = c.kn, s.ks = c.ks, s.ktor = c.ktor, s.kben = c.kben, s.contact_fraction = c.s;
  Vector12 q = Vector12::Zero();
  q.segment<3>(6) = R.transpose() * u;
  const Vec3 linear = -(R * (smooth_joint_matrix(s, c.L0, local_normal).middleRows<3>(6) * q));
  EXPECT_LT((linear - joint.Fb).norm(), 1e-6 * expected.norm());
}

// eq. (5): a rigid rotation of the deformed pair (positions and both orientations) rotates
// the force with it and keeps the energy; particle rotations that differ tilt the normal by
// their mean.
TEST(SmoothJoint, OneBondIsObjective)
{
  const Vec3 N = Vec3(0, 0.6, 0.8);
  const BondConstants c = pair_constants(Vec3(0.2, 0.3, 0.9).normalized());
  BondKinematics k = at_rest(c);
  k.xb += 2e-6 * Vec3(1, -0.5, 0.3);
  k.qa = Quat(Eigen::AngleAxisd(1e-3, Vec3::UnitX()));
  const BondResult before = evaluate_bond<false>(k, c, &N);
  const Quat Q(Eigen::AngleAxisd(1.2, Vec3(1, 1, 0.2).normalized()));
  BondKinematics turned = k;
  turned.xa = Q * k.xa, turned.xb = Q * k.xb, turned.qa = Q * k.qa, turned.qb = Q * k.qb;
  const BondResult after = evaluate_bond<false>(turned, c, &N);
  EXPECT_LT((after.Fc - Q * before.Fc).norm(), 1e-10 * before.Fc.norm());
  EXPECT_NEAR(after.strain_energy, before.strain_energy, 1e-10 * before.strain_energy);
  EXPECT_EQ(after.Mc.norm(), 0.0);
}

namespace
{
constexpr double radius = 1e-3, tau_c = 1e6, sigma_t = 2e6; // m, Pa

struct ShearResult
{
  long crossing = 0;    ///< bonds the plane crosses
  double stiffness = 0; ///< N/m per crossing bond: R.t / (u n), R the upper block's reaction
  double peak = 0;      ///< N per crossing bond: the largest R.t
  double kn = 0, ks = 0, area = 0;
  /// The unified law's closed form: the mean over the crossing bonds of k_n (e_0.t)^2 +
  /// k_s (1 - (e_0.t)^2), the stiffness of a bond along e_0 against a slip along t
  double axial_stiffness = 0;
  double record_mismatch = 0; ///< largest |solver's bond force - scalar kernel's| / |F|
};

/// A simple cubic lattice 10 x 10 x 3 (parallel bonds, kn = 2.5 ks), one weak plane through
/// its centre with normal (cos theta, sin theta, 0), brittle bonds of equal strengths. The block
/// below the plane held, the block above slipped by u along t = (-sin theta, cos theta, 0) in
/// steps (every particle's motion prescribed, rotations none), the explicit solver's bond loop
/// with failure at each slip.
ShearResult rigid_block_shear(double theta, bool smooth)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::cubic;
  c.particles.radius = radius;
  c.particles.box_size = Vec3(20 * radius, 20 * radius, 6 * radius);
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.stiffness_ratio = 2.5;
  c.damage.law.mode = FailureMode::brittle;
  c.damage.tensile_strength = sigma_t;
  c.damage.shear_strength = tau_c;
  const Vec3 n(std::cos(theta), std::sin(theta), 0), t(-std::sin(theta), std::cos(theta), 0);
  WeakPlaneSet plane;
  plane.normal = n;
  plane.offsets = {n.dot(Vec3(10 * radius, 10 * radius, 0)) + 0.37 * radius};
  c.microstructure.weak_planes = plane;
  c.microstructure.smooth_joint = smooth;
  Model m = build_model(c);
  ParticleStore& p = m.particles;
  ShearResult r;
  r.crossing = long(m.microstructure.bonds_per_class[std::size_t(BondClass::weak_plane)]);
  r.kn = m.bonds.kn[0], r.ks = m.bonds.ks[0];
  r.area = std::numbers::pi * m.bonds.radius[0] * m.bonds.radius[0];
  for (std::size_t k = 0; k < m.bonds.size(); ++k)
    if (m.bonds.bond_class[k] == BondClass::weak_plane)
    {
      const double c2 = std::pow(m.bonds.rest_axis[k].dot(t), 2);
      r.axial_stiffness += (r.kn * c2 + r.ks * (1 - c2)) / double(r.crossing);
    }
  std::vector<int> upper;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (n.dot(p.reference_position[i]) > plane.offsets[0])
      upper.push_back(int(i));
  std::vector<int> all(p.size());
  std::iota(all.begin(), all.end(), 0);
  ExplicitSolver solver(p, m.bonds, {{"all", all}}, {{0, 63}}, {}, {1e-7, 0.0, 1});
  const double u_break = tau_c * r.area / r.ks; // the smooth joint's bonds' slip at failure
  const int steps = 400;
  for (int i = 1; i <= steps; ++i)
  {
    const double u = 1.5 * u_break * i / steps;
    for (int j : upper)
      p.position[std::size_t(j)] = p.reference_position[std::size_t(j)] + u * t;
    solver.step(true);
    double F = 0; // the supports' reaction along t: what holds the slip against the joint
    for (int j : upper)
      F += solver.support_reaction(std::size_t(j))[0] * t.x() +
           solver.support_reaction(std::size_t(j))[1] * t.y();
    if (i == 1)
    {
      r.stiffness = F / (u * double(r.crossing));
      for (std::size_t k = 0; k < m.bonds.size(); ++k) // the SIMD loop against the kernel
      {
        const BondContactForce s = bond_contact_force(p, m.bonds, k);
        const double scale = std::max(m.bonds.force[k].norm(), 1e-30);
        r.record_mismatch =
            std::max(r.record_mismatch, (s.force - m.bonds.force[k]).norm() / scale);
      }
    }
    r.peak = std::max(r.peak, F / double(r.crossing));
  }
  return r;
}
} // namespace

// The closed forms of the rigid-block shear at tilts 0, 30 and 60 degrees: with smooth joints
// the stiffness per crossing bond is k_s (to the slip's second order) and the peak tau_c A (to
// the slip step, 1.5/400); the plain bonds' stiffness is their axes' closed form, above k_s at
// a tilt, and their peak differs by more than 20 %.
TEST(SmoothJoint, RigidBlockShearIsIndependentOfTheTilt)
{
  for (double theta : {0.0, 30.0, 60.0})
  {
    const ShearResult joint = rigid_block_shear(theta * deg, true);
    const ShearResult plain = rigid_block_shear(theta * deg, false);
    const double peak = tau_c * joint.area;
    std::cout << "theta " << theta << ": " << joint.crossing
              << " crossing bonds; per bond stiffness / k_s: smooth 1 + "
              << joint.stiffness / joint.ks - 1 << ", plain " << plain.stiffness / joint.ks
              << "; peak / (tau_c A): smooth " << joint.peak / peak << ", plain "
              << plain.peak / peak << "; solver vs kernel " << joint.record_mismatch << "\n";
    EXPECT_GT(joint.crossing, 20);
    EXPECT_NEAR(joint.stiffness / joint.ks, 1.0, 1e-5);
    EXPECT_LE(joint.peak / peak, 1.0 + 1e-9);
    EXPECT_GE(joint.peak / peak, 1.0 - 1.5 / 400 - 1e-3);
    EXPECT_LT(joint.record_mismatch, 1e-9);
    EXPECT_NEAR(plain.stiffness / plain.axial_stiffness, 1.0, 1e-5);
    if (theta > 0)
    {
      EXPECT_GT(plain.stiffness / joint.ks, 1.2);
      EXPECT_GT(std::abs(plain.peak / peak - 1), 0.2); // its bonds' axes carry part of the slip
    }
    else // along its own axis a joint is the bond
      EXPECT_NEAR(plain.peak / joint.peak, 1.0, 1e-3);
  }
}
