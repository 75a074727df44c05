// The bond dashpot against the damped oscillator. Two free spheres on one bond, set moving apart
// along the bond axis, oscillate in the relative coordinate u with the reduced mass m_red:
//   m_red u'' + c_t u' + k_n u = 0,   c_t = xi 2 sqrt(k_n m_red) / sqrt(C / 3)
// (thesis eq. 36-37, C the pair's mean coordination, here 1), so the damping ratio is
// zeta = xi sqrt(3 / C) and successive maxima of u shrink by exp(-2 pi zeta / sqrt(1 - zeta^2))
// (the logarithmic decrement). zeta from the decrement of the first five periods within 1e-3
// of xi sqrt(3) (the step is 1/4000 of the period), for xi = 0.02 and 0.1; the energy the dashpot
// takes closes the balance (thesis eq. 53) within 1e-6.
#include "dem/bonds/bonding.h"
#include "dem/solvers/explicit_solver.h"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

using namespace dembridge::dem;

TEST(BondDamping, AxialOscillationDecaysWithTheDampingRatio)
{
  const double pi = std::numbers::pi, radius = 0.01, speed = 1e-3;
  for (const double xi : {0.02, 0.1})
  {
    ParticleStore p;
    BondStore b;
    p.add(Vec3(0, 0, 0), radius, 2500);
    p.add(Vec3(2 * radius, 0, 0), radius, 2500);
    BondMaterial m;
    m.model = BondModel::timoshenko;
    m.youngs_modulus = 4e9;
    add_bond(p, b, m, 0, 1);
    mark_reference_configuration(p);
    assign_bond_damping(p, b, xi);
    const double m_red = 0.5 * p.mass[0], k = b.kn[0];
    const double zeta = xi * std::sqrt(3.0); // eq. 37 with C = 1
    const double period = 2 * pi / (std::sqrt(k / m_red) * std::sqrt(1 - zeta * zeta));
    p.velocity[0] = Vec3(-0.5 * speed, 0, 0), p.velocity[1] = Vec3(0.5 * speed, 0, 0);
    ExplicitSolver solver(p, b, {}, {}, {}, {period / 4000, 0.0, 1});
    std::vector<double> maxima;
    double before = 0, now = 0, worst = 0, largest = 0;
    while (maxima.size() < 6 && solver.time() < 10 * period)
    {
      solver.step(true);
      largest = std::max(largest, solver.energy().largest());
      worst = std::max(worst, solver.energy().error() / largest);
      const double u = (p.position[1] - p.position[0]).norm() - 2 * radius;
      if (now > before && now >= u && now > 0)
        maxima.push_back(now); // the sample before a fall: a maximum of u
      before = now, now = u;
    }
    ASSERT_EQ(maxima.size(), 6u) << xi;
    const double decrement = std::log(maxima[0] / maxima[5]) / 5;
    const double measured = decrement / std::sqrt(4 * pi * pi + decrement * decrement);
    std::printf("xi = %g: zeta from the decrement %.6f, xi sqrt(3) %.6f (rel. %.1e), energy "
                "balance %.1e\n",
                xi, measured, zeta, measured / zeta - 1, worst);
    EXPECT_NEAR(measured, zeta, 1e-3 * zeta) << xi;
    EXPECT_LT(worst, 1e-6) << xi;
  }
}
