// Torsional stiffness of a single bond against the closed form of a circular shaft:
//   M_t = k_tor theta,  k_tor = G J / L,  G = E / (2 (1 + nu)),  J = pi r_b^4 / 2,
// the bond's radius r_b = (radius multiplier) min(R_a, R_b) and L the distance of the centres.
// Every model gives it: the Euler-Bernoulli and Timoshenko bonds by Chen et al. (2022) Table 6
// (0.25 k_n r^2 / (1 + nu)), the parallel bond by Table 1 (0.5 k_s r^2 with k_s = k_n / kappa
// and kappa = 2 (1 + nu) by default, eq. 8). The thesis' parallel bond given per area
// (k̄_n, k̄_s = k̄_n / kappa; thesis eq. 10-11, 16-17) twists with k̄_s J.
// The references below are written from these formulas, not from bond_model.cc:
//   1. the law (bond_kernel.h) on a twist of 1e-4 rad: M_t within 1e-6 of k_tor theta;
//   2. the explicit solver: a sphere on a bond to a clamped one, set spinning about the bond
//      axis, twists to theta_max = w_0 / Omega, Omega^2 = k_tor / I (I = 2/5 m R^2); k_tor read
//      back from the amplitude within 1e-4 (the step is 1/2000 of the period).
#include "dem/bonds/bond_kernel.h"
#include "dem/bonds/bonding.h"
#include "dem/solvers/explicit_solver.h"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>
#include <string>

using namespace dembridge::dem;

namespace
{
constexpr double pi = std::numbers::pi;
constexpr double youngs = 4e9, poisson = 0.3, density = 2500;

/// Two spheres along `axis` (radii ra, rb, centres `length` apart) and their bond.
struct Twist
{
  std::string what;
  BondMaterial material;
  double ra, rb, length;
  Vec3 axis;
  /// G J / L written from the shaft's closed form.
  double closed_form() const
  {
    const double r = material.radius_multiplier * std::min(ra, rb);
    const double polar = 0.5 * pi * std::pow(r, 4);
    if (material.normal_stiffness_per_area > 0) // the thesis' per-area bond: k̄_s J
      return material.normal_stiffness_per_area / material.stiffness_ratio * polar;
    return youngs / (2.0 * (1.0 + poisson)) * polar / length;
  }
};

BondMaterial material(BondModel model, double multiplier = 1.0)
{
  BondMaterial m;
  m.model = model;
  m.youngs_modulus = youngs;
  m.poisson_ratio = poisson;
  m.radius_multiplier = multiplier;
  return m;
}

std::vector<Twist> cases()
{
  std::vector<Twist> all;
  const Vec3 tilted = Vec3(1, -2, 0.5).normalized();
  for (const BondModel model :
       {BondModel::parallel_bond, BondModel::euler_bernoulli, BondModel::timoshenko})
  {
    const std::string name(bond_model_names[int(model)]);
    all.push_back(
        {name + ", equal spheres touching", material(model), 0.01, 0.01, 0.02, Vec3::UnitX()});
    all.push_back({name + ", unequal spheres with a gap, r_b = 0.8 min(R)", material(model, 0.8),
                   0.01, 0.015, 0.027, tilted});
  }
  BondMaterial per_area = material(BondModel::parallel_bond);
  per_area.normal_stiffness_per_area = youngs / (2 * 0.01); // thesis section 5.1: E_b / (2 r)
  per_area.stiffness_ratio = 4.2;
  all.push_back(
      {"parallel_bond per area (k̄_n = E_b / 2r, kappa = 4.2)", per_area, 0.01, 0.01, 0.02, tilted});
  return all;
}

void make_pair(const Twist& t, ParticleStore& p, BondStore& b)
{
  p.add(Vec3(0.1, 0.2, -0.1), t.ra, density);
  p.add(p.position[0] + t.length * t.axis, t.rb, density);
  add_bond(p, b, t.material, 0, 1);
}
} // namespace

// The law on a twist of +-theta/2 of the two spheres about the bond axis: the couple on b is
// -k_tor theta about the axis, the couple on a its opposite, no force.
TEST(BondTorsion, LawTwistsWithTheShaftStiffness)
{
  for (const Twist& t : cases())
  {
    ParticleStore p;
    BondStore b;
    make_pair(t, p, b);
    const BondConstants c{b.rest_length[0], b.rest_axis[0],        b.kn[0], b.ks[0], b.ktor[0],
                          b.kben[0],        b.contact_fraction[0], 0,       0};
    const double theta = 1e-4;
    const Quat qa(Eigen::AngleAxisd(-0.5 * theta, t.axis)),
        qb(Eigen::AngleAxisd(0.5 * theta, t.axis));
    const BondResult r = evaluate_bond({p.position[0], p.position[1], qa, qb, Vec3::Zero(),
                                        Vec3::Zero(), Vec3::Zero(), Vec3::Zero()},
                                       c);
    const double expected = t.closed_form() * theta;
    std::printf("%s: M_t %.9e N m, G J / L theta %.9e N m (rel. %.1e)\n", t.what.c_str(),
                -r.Mb.dot(t.axis), expected, -r.Mb.dot(t.axis) / expected - 1);
    EXPECT_NEAR(-r.Mb.dot(t.axis), expected, 1e-6 * expected) << t.what;
    EXPECT_NEAR(r.Ma.dot(t.axis), expected, 1e-6 * expected) << t.what;
    EXPECT_LT((r.Mb - r.Mb.dot(t.axis) * t.axis).norm(), 1e-9 * expected) << t.what;
    EXPECT_LT(r.Fb.norm() * t.length, 1e-9 * expected) << t.what;
    // and the stored energy 1/2 k_tor theta^2
    EXPECT_NEAR(r.strain_energy, 0.5 * expected * theta, 1e-6 * 0.5 * expected * theta) << t.what;
  }
}

// Through the explicit solver: sphere a clamped, sphere b free to turn (its translations held),
// started at w_0 about the bond axis. The twist swings as (w_0 / Omega) sin(Omega t) with Omega^2 =
// k_tor / I_b; the largest twist over half a period gives k_tor = I_b (w_0 / theta_max)^2.
TEST(BondTorsion, TorsionalOscillationOfASphereOnABond)
{
  for (const Twist& t : cases())
  {
    ParticleStore p;
    BondStore b;
    make_pair(t, p, b);
    const double mass = density * 4.0 / 3.0 * pi * std::pow(t.rb, 3);
    const double inertia = 0.4 * mass * t.rb * t.rb; // solid sphere
    const double k = t.closed_form(), omega = std::sqrt(k / inertia);
    const double w0 = 1e-3 * omega; // amplitude 1e-3 rad
    p.angular_velocity[1] = w0 * t.axis;
    // a pure twist stays one: the couple is along the axis and the sphere's inertia isotropic
    std::vector<Group> groups{{"clamp", {0}}, {"spinner", {1}}};
    std::vector<Constraint> constraints{
        {0, std::uint8_t(dof_ux | dof_uy | dof_uz | dof_rx | dof_ry | dof_rz)},
        {1, std::uint8_t(dof_ux | dof_uy | dof_uz)}};
    const double period = 2 * pi / omega, dt = period / 2000;
    ExplicitSolver solver(p, b, groups, constraints, {}, {dt, 0.0, 1});
    double theta_max = 0;
    while (solver.time() < 0.5 * period)
    {
      solver.step();
      const Quat relative = p.orientation[0].conjugate() * p.orientation[1];
      const Eigen::AngleAxisd turn(relative);
      theta_max = std::max(theta_max, turn.angle() * std::abs(turn.axis().dot(t.axis)));
    }
    const double k_measured = inertia * std::pow(w0 / theta_max, 2);
    std::printf("%s: k_tor from the swing %.7e N m/rad, G J / L %.7e (rel. %.1e)\n", t.what.c_str(),
                k_measured, k, k_measured / k - 1);
    EXPECT_NEAR(k_measured, k, 1e-4 * k) << t.what;
  }
}
