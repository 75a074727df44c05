// Sliding grain boundaries (bonds/sliding_joints.h, contacts/joint_contact.h) through the contact
// loop: two spheres of two columns whose seeds S_0, S_1 put their boundary's normal
// N = (S_1 - S_0) / |S_1 - S_0| at 30 degrees to the spheres' axis, without a bond. Pressed across
// the boundary by u_n (from the reference positions) and then slid along the boundary by s in
// steps, with linear springs k_n, k_t = 2/7 k_n and the boundaries' friction mu_gb, the force on
// the second sphere is
//   sticking (k_t s <= mu_gb k_n u_n):  F = k_n u_n N - k_t s t
//   sliding:                            F = k_n u_n N - mu_gb k_n u_n t
// with t the sliding direction in the boundary's plane: along the boundary's normal, not the
// spheres' axis, and with the boundary's friction, not the contacts'. The same two spheres in one
// grain meet as spheres (the force along their axis).
#include "dem/bonds/bond_store.h"
#include "dem/contacts/contact_forces.h"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
constexpr double R = 2.5e-3, rho = 917;                            // m, kg/m^3
constexpr double kn = 1.57e7, kt = 2.0 / 7.0 * kn;                 // N/m
constexpr double mu_contacts = 0.5, mu_boundary = 0.1, u_n = 1e-6; // -, -, m
const Vec3 N = Vec3(std::cos(std::numbers::pi / 6), std::sin(std::numbers::pi / 6), 0);
const Vec3 t = Vec3(-N.y(), N.x(), 0); // in the boundary's plane and across the columns (z)

ContactConfig linear_contacts()
{
  ContactConfig m;
  m.model = ContactModel::linear;
  m.normal_stiffness = kn;
  m.restitution = 1.0; // no dashpot: the joint has none either
  m.friction = mu_contacts;
  return m;
}

/// Two spheres touching along x at their reference positions, in grains @p g0 and @p g1 of two
/// columns seeded 10 mm apart along N.
struct TwoColumns
{
  ParticleStore p;
  BondStore bonds;
  ContactForces contacts{linear_contacts(), {}};

  TwoColumns(int g0, int g1)
  {
    p.add(Vec3::Zero(), R, rho);
    p.add(Vec3(2 * R - 1e-9, 0, 0), R, rho);
    p.grain = {g0, g1};
    SlidingJoints joints;
    joints.grain_seed = {Vec3(0.01, 0.02, 0) - 5e-3 * N, Vec3(0.01, 0.02, 0) + 5e-3 * N};
    joints.boundary_friction = mu_boundary;
    bonds.sliding_joints = joints;
    contacts.attach(p, bonds);
  }

  /// The force on sphere 1 at its current position, moving at @p v.
  Vec3 force(const Vec3& v, double dt)
  {
    p.velocity[1] = v;
    p.force[0].setZero(), p.force[1].setZero();
    contacts.add_forces(p, 0.0, dt, false);
    return p.force[1];
  }
};
} // namespace

TEST(SlidingBoundary, SlidesOnTheBisectorOfTheSeedsWithItsFriction)
{
  TwoColumns pair(0, 1);
  const int steps = 400;
  const double dt = 1e-7, slide = 4e-6, ds = slide / steps; // sliding from s = 0.35 um on
  pair.p.position[1] -= u_n * N;
  double max_error = 0;
  for (int n = 0; n <= steps; ++n)
  {
    const Vec3 f = pair.force(n == 0 ? Vec3::Zero() : Vec3(ds / dt * t), dt);
    const double shear = std::min(kt * n * ds, mu_boundary * kn * u_n);
    const Vec3 expected = kn * u_n * N - shear * t;
    max_error = std::max(max_error, (f - expected).norm() / (kn * u_n));
    pair.p.position[1] += ds * t;
  }
  std::printf("grain boundary at 30 degrees to the spheres' axis: largest |F - F_closed| / "
              "(k_n u_n) %.3g over %d steps\n",
              max_error, steps);
  EXPECT_LT(max_error, 1e-9);
}

TEST(SlidingBoundary, SpheresOfOneGrainMeetAsSpheres)
{
  TwoColumns pair(0, 0);
  pair.p.position[1] -= u_n * N; // the same pressing: an overlap along the spheres' axis
  const Vec3 f = pair.force(Vec3::Zero(), 1e-7);
  const Vec3 axis = pair.p.position[1] - pair.p.position[0];
  const double overlap = 2 * R - axis.norm();
  ASSERT_GT(overlap, 0.0);
  EXPECT_NEAR(f.norm(), kn * overlap, 1e-9 * kn * overlap);
  EXPECT_LT((f.normalized() - axis.normalized()).norm(), 1e-9); // along the axis, not N
}
