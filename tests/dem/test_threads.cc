// The slab partition of the bond loop (explicit_solver_bonds.cc) must not change the physics: two
// threads give the one-thread trajectory up to summation order (round-off).
#include "dem/bonds/bonding.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/packing/packings.h"
#include "dem/solvers/time_step.h"
#include <gtest/gtest.h>
#include <random>

using namespace dembridge::dem;

namespace
{
struct Lattice
{
  ParticleStore p;
  BondStore b;
  explicit Lattice(double xi)
  {
    ParticleSource src;
    src.kind = ParticleSource::Kind::hcp;
    src.radius = 5e-3;
    src.box_size = Vec3(0.1, 0.04, 0.04);
    generate_particles(src, p);
    BondMaterial mat;
    mat.youngs_modulus = 4e9;
    form_bonds(p, b, mat, 1.0);
    assign_bond_damping(p, b, xi);
    std::mt19937 rng(3);
    std::normal_distribution<double> n01(0, 1);
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      p.velocity[i] = 1e-2 * Vec3(n01(rng), n01(rng), n01(rng));
      p.angular_velocity[i] = Vec3(n01(rng), n01(rng), n01(rng));
    }
  }
};
} // namespace

TEST(Threads, TwoThreadsReproduceOneThread)
{
  for (double xi : {0.0, 0.1})
  {
    Lattice one(xi), two(xi);
    const double dt = 0.8 * estimate_critical_time_step(one.p, one.b).critical();
    ExplicitSolver s1(one.p, one.b, {}, {}, {}, {dt, 0.0, 1});
    ExplicitSolver s2(two.p, two.b, {}, {}, {}, {dt, 0.0, 2});
    for (int n = 0; n < 200; ++n)
    {
      s1.step(n == 199);
      s2.step(n == 199);
    }
    double max_diff = 0, max_disp = 0;
    for (std::size_t i = 0; i < one.p.size(); ++i)
    {
      max_diff = std::max(max_diff, (one.p.position[i] - two.p.position[i]).norm());
      max_disp = std::max(max_disp, (one.p.position[i] - one.p.reference_position[i]).norm());
    }
    EXPECT_GT(max_disp, 0);
    EXPECT_LT(max_diff, 1e-9 * max_disp) << "xi = " << xi;
    EXPECT_NEAR(s1.energy().strain, s2.energy().strain, 1e-9 * s1.energy().strain);
    EXPECT_LT(s2.energy().relative_error(), 1e-6);
  }
}
