// Mass-proportional damping in the explicit solver (Damping/mass damping, explicit_solver.h):
// the force -c m v^{n-1/2} on every particle's translation, what Coupling/mass damping applies
// in a coupled run, so that a full-DEM run can be damped alike.
//
// A particle on one axial bond to a clamped one is a damped oscillator, m x'' + c m x' + k x = 0
// with omega = sqrt(k / m) and damping ratio xi = c / (2 omega). Its energy after whole damped
// periods T_d = 2 pi / (omega sqrt(1 - xi^2)) is E_0 exp(-c t) exactly. The scheme's own factor
// per step is |lambda|^2 = 1 - c dt (the characteristic polynomial of the lagged update), so
// E(n dt) = E_0 (1 - c dt)^n at the phase returns: tested to 1e-3, the continuous law to 1 %.
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
CaseConfig bonded_pair()
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::row;
  c.particles.count = 2;
  c.particles.radius = 0.01;
  c.particles.density = 1000;
  c.bonds.material.model = BondModel::timoshenko;
  c.bonds.material.youngs_modulus = 1e8;
  c.bonds.material.poisson_ratio = 0.3;
  GroupConfig clamp{"clamp", {}, 63, 0, Vec3::Zero()};
  clamp.selection.kind = GroupSelection::Kind::index;
  clamp.selection.indices = {0};
  c.groups = {clamp};
  return c;
}
} // namespace

TEST(MassDamping, DampedOscillatorLosesEnergyAtRateC)
{
  Model m = build_model(bonded_pair());
  const double k = m.bonds.kn[0], mass = m.particles.mass[1];
  const double omega = std::sqrt(k / mass), xi = 0.05, c = 2 * xi * omega;
  const double period = 2 * std::numbers::pi / (omega * std::sqrt(1 - xi * xi));
  const int steps_per_period = 400;
  const double dt = period / steps_per_period;
  m.particles.velocity[1] = Vec3(1e-3, 0, 0); // axial: only the normal spring works
  ExplicitSolver solver(m.particles, m.bonds, m.groups, m.constraints, m.loads, {dt, 0.0, 1, c});
  solver.step(true);
  const double e0 = solver.energy().initial;
  ASSERT_GT(e0, 0);
  const int periods = 5;
  for (int n = 1; n < periods * steps_per_period; ++n)
    solver.step(n + 1 == periods * steps_per_period);
  const auto& e = solver.energy();
  const double stored = e.kinetic + e.strain;
  const long n_steps = solver.steps();
  const double scheme = e0 * std::pow(1 - c * dt, double(n_steps - 1));
  const double continuous = e0 * std::exp(-c * solver.time());
  EXPECT_NEAR(stored / scheme, 1.0, 1e-3);
  EXPECT_NEAR(stored / continuous, 1.0, 1e-2);
  // what left the oscillator is booked as damping work
  EXPECT_LT(e.error() / e.largest(), 1e-9);
  EXPECT_NEAR(e.damping / (e0 - stored), 1.0, 1e-9);
}

TEST(MassDamping, ZeroDampingLeavesTheRunBitForBit)
{
  auto run = [](double c)
  {
    Model m = build_model(bonded_pair());
    m.particles.velocity[1] = Vec3(1e-3, 2e-4, 0);
    ExplicitSolver solver(m.particles, m.bonds, m.groups, m.constraints, m.loads,
                          {m.time_step, 0.0, 1, c});
    for (int n = 0; n < 500; ++n)
      solver.step(n == 499);
    return m.particles.position[1];
  };
  Model reference = build_model(bonded_pair());
  reference.particles.velocity[1] = Vec3(1e-3, 2e-4, 0);
  ExplicitSolver plain(reference.particles, reference.bonds, reference.groups,
                       reference.constraints, reference.loads, {reference.time_step, 0.0, 1});
  for (int n = 0; n < 500; ++n)
    plain.step(n == 499);
  EXPECT_EQ(run(0.0), reference.particles.position[1]);
  EXPECT_NE(run(10.0), reference.particles.position[1]);
}

TEST(MassDamping, RefusesAnUnstableRate)
{
  Model m = build_model(bonded_pair());
  EXPECT_THROW(ExplicitSolver(m.particles, m.bonds, m.groups, m.constraints, m.loads,
                              {m.time_step, 0.0, 1, 1.0 / m.time_step}),
               InputError);
  EXPECT_THROW(ExplicitSolver(m.particles, m.bonds, m.groups, m.constraints, m.loads,
                              {m.time_step, 0.0, 1, -1.0}),
               InputError);
}
