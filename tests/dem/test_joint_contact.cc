// The unbonded smooth joint (dem/contacts/joint_contact.h) against its closed forms: two
// spheres across a plane of normal N = x, their axis at 0, 30 or 60 degrees to N, j pressed
// across the plane by u_n and then slid along it by s in steps. With linear springs k_n, k_t:
//   sticking (k_t s <= mu_j k_n u_n):  F = k_n u_n N - k_t s t
//   sliding:                           F = k_n u_n N - mu_j k_n u_n t
// with t the sliding direction, whatever the pair's axis (no interlocking: two spheres would
// push apart along their axis and ride up); the energy stored plus the slip's dissipation
// equals the work done on the pair (trapezoid rule, the leapfrog's), to round-off. The shear
// handed over from a broken bond is the in-plane displacement, capped at mu_j F_n / k_t.
#include "dem/contacts/joint_contact.h"
#include "dem/contacts/linear_spring_dashpot.h"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
constexpr double kn = 2e7, kt = 8e6, mu_j = 0.5, u_n = 1e-6; // N/m, N/m, -, m
const LinearSpringDashpot springs{kn, kt, 0.0};
} // namespace

TEST(JointContact, SlidesOnThePlaneWhateverTheAxis)
{
  const Vec3 N = Vec3::UnitX(), t = Vec3::UnitY();
  const int steps = 400;
  const double dt = 1e-7, slide = 4e-6, ds = slide / steps; // stick up to 1.25e-6 m
  for (double tilt : {0.0, 30.0, 60.0})
  {
    const double a = tilt * std::numbers::pi / 180;
    const Vec3 X_i = Vec3::Zero(), X_j = 3e-3 * Vec3(std::cos(a), std::sin(a), 0);
    Vec3 x_j = X_j - u_n * N, xi = Vec3::Zero();
    double k_old = 0, work = 0, slip = 0, energy = 0;
    Vec3 force_before = Vec3::Zero();
    for (int n = 0; n <= steps; ++n)
    {
      const double approach = joint_approach(N, X_i, x_j, X_i, X_j);
      ASSERT_NEAR(approach, u_n, 1e-18);
      const Vec3 v_rel = n == 0 ? Vec3::Zero() : Vec3(ds / dt * t);
      const JointContactOutput out =
          joint_contact_force(springs, N, approach, v_rel, 0.0, 1.0, mu_j, dt, xi, k_old);
      const double s = n * ds;
      const double shear = std::min(kt * s, mu_j * kn * u_n);
      const Vec3 expected = kn * u_n * N - shear * t;
      EXPECT_LT((out.force - expected).norm(), 1e-9 * kn * u_n) << "tilt " << tilt << " s " << s;
      EXPECT_EQ(out.force.z(), 0.0);
      if (n > 0) // work of the force on j over the step, trapezoid rule
        work += 0.5 * (force_before + out.force).dot(ds * t);
      force_before = out.force;
      slip += out.slip;
      energy = out.energy;
      x_j += ds * t;
    }
    const double stored0 = 0.5 * kn * u_n * u_n;
    // the pressing's energy was there from the first step; what the sliding put in is stored or
    // dissipated
    EXPECT_NEAR(energy - stored0 + slip, -work, 1e-12 * std::abs(work)) << "tilt " << tilt;
    EXPECT_GT(slip, 0.0);
  }
}

TEST(JointContact, HandsOverTheBondsShearCapped)
{
  const Vec3 N = Vec3::UnitX();
  const Vec3 X_i = Vec3::Zero(), X_j = Vec3(3e-3, 1e-3, 0);
  const double f_n = kn * u_n;
  // within the cap: the in-plane displacement itself (the normal part dropped)
  Vec3 x_j = X_j + Vec3(-u_n, 0.2e-6, 0.1e-6);
  Vec3 xi = joint_shear_handover(N, X_i, x_j, X_i, X_j, kt, mu_j, f_n);
  EXPECT_LT((xi - Vec3(0, 0.2e-6, 0.1e-6)).norm(), 1e-18);
  // beyond it: along the displacement, at mu_j F_n / k_t
  x_j = X_j + Vec3(-u_n, 3e-6, -4e-6);
  xi = joint_shear_handover(N, X_i, x_j, X_i, X_j, kt, mu_j, f_n);
  EXPECT_NEAR(kt * xi.norm(), mu_j * f_n, 1e-12 * f_n);
  EXPECT_LT((xi.normalized() - Vec3(0, 0.6, -0.8)).norm(), 1e-12);
}
