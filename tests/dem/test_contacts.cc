// Post-failure contacts and walls (dem/contacts/): the Chung & Ooi (2011) benchmarks, the
// restitution of the linear law, friction on an incline, rolling resistance, the tangential
// spring under rigid rotation, the energy balance through impacts, bonded pairs, and the Verlet
// list against an all-pairs search.
#include "dem/bonds/bonding.h"
#include "dem/contacts/contact_forces.h"
#include "dem/contacts/neighbour_list.h"
#include "dem/solvers/explicit_solver.h"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <memory>
#include <numbers>
#include <random>
#include <set>

using namespace dembridge::dem;

namespace
{
constexpr double g = 9.81;

/// Particles, no bonds unless added, contacts and an explicit solver.
struct Scene
{
  ParticleStore p;
  BondStore b;
  std::unique_ptr<ContactForces> contacts;
  std::unique_ptr<ExplicitSolver> solver;
  std::vector<Group> groups;
  std::vector<Constraint> constraints;
  std::vector<Load> loads;

  int add(const Vec3& x, double r, double rho, const Vec3& v = Vec3::Zero())
  {
    p.add(x, r, rho);
    p.velocity.back() = v;
    return int(p.size()) - 1;
  }
  /// Constant force on particle i (gravity: m g).
  void push(int i, const Vec3& f)
  {
    groups.push_back({"g" + std::to_string(groups.size()), {i}});
    Load l;
    l.group = int(groups.size()) - 1;
    l.value = f;
    loads.push_back(l);
  }
  void hold_rotation(int i)
  {
    groups.push_back({"r" + std::to_string(groups.size()), {i}});
    constraints.push_back({int(groups.size()) - 1, std::uint8_t(dof_rx | dof_ry | dof_rz)});
  }
  void start(const ContactMaterial& m, const std::vector<WallConfig>& walls, double dt)
  {
    contacts = std::make_unique<ContactForces>(m, walls);
    solver = std::make_unique<ExplicitSolver>(p, b, groups, constraints, loads,
                                              SolverSettings{dt, 0.0, 1});
    solver->add_contribution(contacts.get());
  }
};

ContactMaterial hertz(double E, double nu, double e = 1.0, double mu = 0.0)
{
  ContactMaterial m;
  m.model = ContactModel::hertz_mindlin;
  m.youngs_modulus = E;
  m.poisson_ratio = nu;
  m.restitution = e;
  m.friction = mu;
  m.monitor = true;
  return m;
}

ContactMaterial linear(double kn, double e = 1.0, double mu = 0.0)
{
  ContactMaterial m;
  m.model = ContactModel::linear;
  m.normal_stiffness = kn;
  m.restitution = e;
  m.friction = mu;
  m.monitor = true;
  return m;
}

WallConfig floor_wall(const Vec3& normal = Vec3::UnitZ(), const Vec3& point = Vec3::Zero())
{
  WallConfig w;
  w.name = "floor";
  w.point = point;
  w.normal = normal;
  return w;
}

/// Runs until the monitored contact has ended (or max_steps), recording every step; returns the
/// largest energy balance error relative to the largest term seen so far (run_explicit's rule).
double run_contact(Scene& s, long max_steps)
{
  double worst = 0, largest = 0;
  for (long n = 0; n < max_steps && !s.contacts->monitor().finished; ++n)
  {
    s.solver->step(true);
    largest = std::max(largest, s.solver->energy().largest());
    worst = std::max(worst, s.solver->energy().error() / largest);
  }
  return worst;
}
} // namespace

// Chung & Ooi (2011), test 1: elastic normal impact of two equal glass spheres at +-10 m/s.
TEST(ContactBenchmarks, ChungOoiTwoGlassSpheres)
{
  const double R = 0.01, rho = 2800, v = 10.0;
  Scene s;
  s.add(Vec3(-R - 1e-6, 0, 0), R, rho, Vec3(v, 0, 0));
  s.add(Vec3(R + 1e-6, 0, 0), R, rho, Vec3(-v, 0, 0));
  s.start(hertz(48e9, 0.20), {}, 2e-8);
  const double error = run_contact(s, 10000);
  const auto& mon = s.contacts->monitor();
  ASSERT_TRUE(mon.finished);
  std::printf("two glass spheres: max overlap %.5g m, max force %.5g N, contact time %.5g s, "
              "e %.6f, energy balance %.2e\n",
              mon.max_overlap, mon.max_force, mon.duration(), mon.restitution(), error);
  EXPECT_NEAR(mon.max_overlap, 274.1e-6, 0.01 * 274.1e-6);
  EXPECT_NEAR(mon.max_force, 10.70e3, 0.01 * 10.70e3);
  EXPECT_NEAR(mon.duration(), 40.34e-6, 0.01 * 40.34e-6);
  EXPECT_NEAR(mon.restitution(), 1.0, 1e-3); // elastic
  EXPECT_LT(error, 0.01);
}

// Chung & Ooi (2011), test 2: an aluminium-alloy sphere hits a rigid wall at 0.2 m/s.
TEST(ContactBenchmarks, ChungOoiAluminiumSphereOnWall)
{
  const double R = 0.1, rho = 2699, v = 0.2;
  Scene s;
  s.add(Vec3(0, 0, R + 1e-7), R, rho, Vec3(0, 0, -v));
  s.start(hertz(70e9, 0.30), {floor_wall()}, 2e-7);
  const double error = run_contact(s, 20000);
  const auto& mon = s.contacts->monitor();
  ASSERT_TRUE(mon.finished);
  EXPECT_TRUE(mon.wall);
  std::printf("aluminium sphere on a wall: max overlap %.5g m, max force %.5g N, contact time "
              "%.5g s, energy balance %.2e\n",
              mon.max_overlap, mon.max_force, mon.duration(), error);
  EXPECT_NEAR(mon.max_overlap, 49.72e-6, 0.01 * 49.72e-6);
  EXPECT_NEAR(mon.max_force, 11.37e3, 0.01 * 11.37e3);
  EXPECT_NEAR(mon.duration(), 0.7316e-3, 0.01 * 0.7316e-3);
  EXPECT_LT(error, 0.01);
}

// The linear law's dashpot is set from e so that a free pair rebounds with e (displacement
// criterion for the end of the contact).
TEST(ContactBenchmarks, LinearLawReturnsItsRestitution)
{
  for (double e : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0})
  {
    Scene s;
    const double R = 0.01, v = 1.0;
    s.add(Vec3(-R - 1e-7, 0, 0), R, 2500, Vec3(v, 0, 0));
    s.add(Vec3(R + 1e-7, 0, 0), R, 2500, Vec3(-v, 0, 0));
    s.start(linear(1e6, e), {}, 1e-6); // contact time pi sqrt(m*/k) = 0.2 ms: 200 steps
    const double error = run_contact(s, 100000);
    ASSERT_TRUE(s.contacts->monitor().finished) << "e = " << e;
    std::printf("linear law, e = %.1f: rebound %.5f, energy balance %.2e\n", e,
                s.contacts->monitor().restitution(), error);
    EXPECT_NEAR(s.contacts->monitor().restitution(), e, 0.01 * e) << "e = " << e;
    EXPECT_LT(error, 0.01) << "e = " << e;
  }
}
