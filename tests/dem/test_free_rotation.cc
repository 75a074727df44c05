// The explicit solver's orientation update (explicit_solver.cc, thesis eq. 45 in quaternion
// form): q <- exp(dt w / 2) q, normalised each step. A free sphere spinning at a constant
// angular velocity w about a fixed axis has the exact orientation q(t) = exp(t w / 2): the
// update composes N rotations by dt |w| about the same axis, so after N steps the orientation is
// the rotation by N dt |w| up to roundoff, and |q| stays 1 to roundoff. Both branches of the
// update: the small-angle series (|dt w / 2|^2 < 1e-6) and cos / sin; and both paths of the
// solver (orientation_update.h): nine spheres about nine axes, eight of them in a block of SIMD
// lanes and the ninth alone, and a block whose one fast sphere sends all eight to the one-at-a-
// time path.
#include "dem/solvers/explicit_solver.h"
#include <Eigen/Geometry>
#include <cmath>
#include <gtest/gtest.h>
#include <utility>
#include <vector>

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

/// Spins sphere k at omega[k] about axis k for the steps; returns the largest distance from the
/// exact rotation and the largest ||q| - 1| over the spheres and steps.
std::pair<double, double> spin(const std::vector<double>& omega, double dt, long steps)
{
  ParticleStore p;
  std::vector<Vec3> axis;
  for (std::size_t k = 0; k < omega.size(); ++k)
  {
    p.add(Vec3(0.03 * double(k), 0, 0), 0.01, 1000);
    axis.push_back(Vec3(1.0 + double(k), 2.0 - double(k), -2.0 + 0.5 * double(k)).normalized());
    p.angular_velocity[k] = omega[k] * axis[k];
  }
  BondStore b;
  ExplicitSolver solver(p, b, {}, {}, {}, {dt, 0.0, 1});
  double worst_norm = 0, distance = 0;
  for (long n = 0; n < steps; ++n)
  {
    solver.step(false);
    for (std::size_t k = 0; k < omega.size(); ++k)
      worst_norm = std::max(worst_norm, std::abs(p.orientation[k].norm() - 1.0));
  }
  for (std::size_t k = 0; k < omega.size(); ++k)
  {
    const Quat exact(Eigen::AngleAxisd(double(steps) * dt * omega[k], axis[k]));
    // q and -q are the same rotation
    distance = std::max(distance, std::min((p.orientation[k].coeffs() - exact.coeffs()).norm(),
                                           (p.orientation[k].coeffs() + exact.coeffs()).norm()));
    EXPECT_EQ(p.angular_velocity[k], omega[k] * axis[k]); // no torque: w is constant
  }
  return {distance, worst_norm};
}

TEST_P(FreeRotation, OrientationIsTheExactRotationAndStaysUnit)
{
  const Spin c = GetParam();
  const auto [distance, worst_norm] = spin(std::vector<double>(9, c.omega), c.dt, c.steps);
  std::cout << "angle " << double(c.steps) * c.dt * c.omega << " rad: |q - q_exact| " << distance
            << ", max ||q| - 1| " << worst_norm << "\n";
  // roundoff of ~1e-16 a step, accumulated over the steps (a random walk in the angle)
  EXPECT_LT(distance, 1e-10);
  EXPECT_LT(worst_norm, 1e-14);
}

// One sphere of a block of eight turning past the series' range: the block takes the
// one-at-a-time path, each sphere its own branch, all of them exact.
TEST(FreeRotation, BlockWithOneFastSphereStaysExact)
{
  std::vector<double> omega(8, 10.0);
  omega[3] = 1000.0; // |dt w / 2|^2 = 2.5e-5
  const auto [distance, worst_norm] = spin(omega, 1e-5, 20000);
  EXPECT_LT(distance, 1e-11);
  EXPECT_LT(worst_norm, 1e-14);
}

INSTANTIATE_TEST_SUITE_P(SeriesAndTrigonometric, FreeRotation,
                         ::testing::Values(Spin{10.0, 1e-5, 200000},   // |dt w / 2|^2 = 2.5e-9
                                           Spin{1000.0, 1e-5, 200000}, // 2.5e-5: cos / sin
                                           Spin{3e4, 1e-5, 20000}),    // 0.0225: 17 turns a ms
                         [](const auto& info)
                         { return "omega_" + std::to_string(int(info.param.omega)); });
} // namespace
