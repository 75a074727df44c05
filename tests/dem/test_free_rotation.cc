// The explicit solver's orientation update (explicit_solver.cc, thesis eq. 45 in quaternion
// form): q <- exp(dt w / 2) q, normalised each step. A free sphere spinning at a constant
// angular velocity w about a fixed axis has the exact orientation q(t) = exp(t w / 2): the
// update composes N rotations by dt |w| about the same axis, so after N steps the orientation is
// the rotation by N dt |w| up to roundoff, and |q| stays 1 to roundoff. Both branches of the
// update: the small-angle series (|dt w / 2|^2 < 1e-6) and cos / sin.
#include "dem/solvers/explicit_solver.h"
#include <Eigen/Geometry>
#include <cmath>
#include <gtest/gtest.h>

using namespace dembridge::dem;

namespace
{
struct Spin
{
  double omega; ///< rad/s
  double dt;    ///< s
  long steps;
};

class FreeRotation : public ::testing::TestWithParam<Spin>
{
};

TEST_P(FreeRotation, OrientationIsTheExactRotationAndStaysUnit)
{
  const Spin c = GetParam();
  ParticleStore p;
  p.add(Vec3::Zero(), 0.01, 1000);
  const Vec3 axis = Vec3(1, 2, -2).normalized();
  p.angular_velocity[0] = c.omega * axis;
  BondStore b;
  ExplicitSolver solver(p, b, {}, {}, {}, {c.dt, 0.0, 1});
  double worst_norm = 0;
  for (long n = 0; n < c.steps; ++n)
  {
    solver.step(false);
    worst_norm = std::max(worst_norm, std::abs(p.orientation[0].norm() - 1.0));
  }
  const Quat exact(Eigen::AngleAxisd(double(c.steps) * c.dt * c.omega, axis));
  // q and -q are the same rotation
  const double distance = std::min((p.orientation[0].coeffs() - exact.coeffs()).norm(),
                                   (p.orientation[0].coeffs() + exact.coeffs()).norm());
  std::cout << "angle " << double(c.steps) * c.dt * c.omega << " rad: |q - q_exact| " << distance
            << ", max ||q| - 1| " << worst_norm << "\n";
  // roundoff of ~1e-16 a step, accumulated over the steps (a random walk in the angle)
  EXPECT_LT(distance, 1e-10);
  EXPECT_LT(worst_norm, 1e-14);
  EXPECT_EQ(p.angular_velocity[0], c.omega * axis); // no torque: w is constant
}

INSTANTIATE_TEST_SUITE_P(SeriesAndTrigonometric, FreeRotation,
                         ::testing::Values(Spin{10.0, 1e-5, 200000},   // |dt w / 2|^2 = 2.5e-9
                                           Spin{1000.0, 1e-5, 200000}, // 2.5e-5: cos / sin
                                           Spin{3e4, 1e-5, 20000}),    // 0.0225: 17 turns a ms
                         [](const auto& info)
                         { return "omega_" + std::to_string(int(info.param.omega)); });
} // namespace
