// Bond failure: a single bond of each model, driven kinematically in pure tension,
// shear, bending and torsion, fails at the load beam theory on its section gives (bond_stress.h:
// sigma = F_n/A + beta |M_b| R/I, tau = |F_s|/A + beta |M_t| R/J), within 0.1 %; Mohr-Coulomb
// shear strength c + sigma_c tan(phi); a softening bond dissipates G_f A (bond_damage.h eq. 4)
// whatever the time step; a brittle break books the bond's energy as fracture so that the
// energy balance (thesis eq. 53) closes; broken stays broken; seeded strengths; bad input.
#include "dem/bonds/bond_strength.h"
#include "dem/bonds/bond_stress.h"
#include "dem/bonds/bonding.h"
#include "dem/packing/packings.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/time_step.h"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
constexpr double radius = 0.01;                             // particles and bond, m
constexpr double area = std::numbers::pi * radius * radius; // A
constexpr double inertia = 0.25 * area * radius * radius;   // I = pi R^4 / 4
constexpr double polar = 0.5 * std::numbers::pi * radius * radius * radius * radius; // J

DamageConfig brittle(double sigma_t, double tau_c, double beta = 1.0)
{
  DamageConfig d;
  d.law.mode = FailureMode::brittle;
  d.law.moment_factor = beta;
  d.tensile_strength = sigma_t;
  d.shear_strength = tau_c;
  return d;
}

/// Two touching spheres joined by one bond; particle 0 is "a", particle 1 is "b" (axis +x).
struct BondedPair
{
  ParticleStore p;
  BondStore b;
  std::vector<Load> loads;
  BondedPair(BondModel model, const DamageConfig& damage)
  {
    ParticleSource src;
    src.kind = ParticleSource::Kind::row;
    src.count = 2;
    src.radius = radius;
    src.density = 1000;
    generate_particles(src, p);
    BondMaterial mat;
    mat.model = model;
    mat.youngs_modulus = 4e9;
    mat.poisson_ratio = 0.3;
    add_bond(p, b, mat, 0, 1);
    mark_reference_configuration(p);
    assign_bond_strengths(b, damage);
  }
  /// Prescribed velocities and angular velocities of both particles (every DOF): kinematic.
  void drive(const Vec3& va, const Vec3& wa, const Vec3& vb, const Vec3& wb)
  {
    int g = 0;
    for (const auto& [v, w] : {std::pair{va, wa}, std::pair{vb, wb}})
    {
      loads.push_back({.name = "v", .group = g, .kind = LoadKind::velocity, .value = v});
      loads.push_back({.name = "w", .group = g, .kind = LoadKind::angular_velocity, .value = w});
      ++g;
    }
  }
  std::vector<Group> groups() const { return {{"a", {0}}, {"b", {1}}}; }
};

struct RunUntilBroken
{
  double time = -1;       ///< time of the crack event (s); -1: never broke
  Vec3 force, moment;     ///< contact force / couple on b at the last step before the break
  Vec3 axis;              ///< bond axis a -> b at that step
  double peak_normal = 0; ///< largest tensile normal force seen (N)
  CrackEvent crack;
  EnergyBalance energy;
  double worst_balance = 0; ///< max over the run of |balance| / largest component so far
};

RunUntilBroken run(BondedPair& s, double dt, long max_steps, long after = 0)
{
  ExplicitSolver solver(s.p, s.b, s.groups(), {}, s.loads, {dt, 0.0, 1});
  RunUntilBroken r;
  double largest = 0;
  long extra = -1;
  for (long n = 0; n < max_steps && extra != 0; ++n, extra -= extra > 0)
  {
    const Vec3 F = s.b.force[0], M = s.b.moment[0];
    const Vec3 axis = (s.p.position[1] - s.p.position[0]).normalized();
    solver.step(true);
    largest = std::max(largest, solver.energy().largest());
    r.worst_balance = std::max(r.worst_balance, solver.energy().error() / largest);
    if (s.b.state[0] == BondState::broken && r.time < 0)
    {
      r.time = solver.cracks().at(0).time;
      r.crack = solver.cracks()[0];
      r.force = F, r.moment = M, r.axis = axis;
      extra = after;
    }
    else if (s.b.state[0] != BondState::broken)
      r.peak_normal = std::max(r.peak_normal, -s.b.force[0].x());
  }
  r.energy = solver.energy();
  return r;
}

constexpr double dt = 1e-6;           // kinematic runs: any step is stable
constexpr double steps_to_fail = 2e4; // load increment per step 5e-5 of the failure load

class BondFailure : public ::testing::TestWithParam<BondModel>
{
};
} // namespace

// Pure tension: F_n = sigma_t A, reached at the stretch sigma_t A / k_n.
TEST_P(BondFailure, PureTension)
{
  const double sigma_t = 1e6;
  BondedPair s(GetParam(), brittle(sigma_t, 5e6));
  const double stretch = sigma_t * area / s.b.kn[0];
  const double t_fail = steps_to_fail * dt, v = stretch / t_fail;
  s.drive(Vec3::Zero(), Vec3::Zero(), Vec3(v, 0, 0), Vec3::Zero());
  const auto r = run(s, dt, long(2 * steps_to_fail));
  ASSERT_GT(r.time, 0);
  EXPECT_NEAR(r.time, t_fail, 1e-3 * t_fail);
  EXPECT_NEAR(-r.force.x(), sigma_t * area, 1e-3 * sigma_t * area); // F_n = -F_c . e
  EXPECT_EQ(r.crack.mode, CrackMode::tension);
  EXPECT_EQ(s.p.coordination[0], 0);
  EXPECT_EQ(s.p.coordination[1], 0);
}

// Pure shear (both particles rotation-locked, b moved across the axis): the contact couple
// vanishes, |F_s| = tau_c A at the shear displacement tau_c A / k_s.
TEST_P(BondFailure, PureShear)
{
  const double tau_c = 1.5e6;
  BondedPair s(GetParam(), brittle(5e6, tau_c));
  const double slide = tau_c * area / s.b.ks[0];
  const double t_fail = steps_to_fail * dt, v = slide / t_fail;
  s.drive(Vec3::Zero(), Vec3::Zero(), Vec3(0, v, 0), Vec3::Zero());
  const auto r = run(s, dt, long(2 * steps_to_fail));
  ASSERT_GT(r.time, 0);
  EXPECT_NEAR(r.time, t_fail, 1e-3 * t_fail);
  const Vec3 e = Vec3::UnitX();
  EXPECT_NEAR((r.force - r.force.dot(e) * e).norm(), tau_c * area, 1e-3 * tau_c * area);
  EXPECT_LT(r.moment.norm(), 1e-9 * tau_c * area * radius);
  EXPECT_EQ(r.crack.mode, CrackMode::shear);
}

// Pure bending (a and b rotated opposite ways about y, so no shear at the contact point):
// sigma = beta |M_b| R / I = sigma_t at M_b = sigma_t I / (beta R), the relative rotation
// M_b / k_ben. With beta = 1/2 the moment at failure doubles.
TEST_P(BondFailure, PureBending)
{
  const double sigma_t = 1e6;
  for (double beta : {1.0, 0.5})
  {
    BondedPair s(GetParam(), brittle(sigma_t, 1e9, beta));
    const double moment = sigma_t * inertia / (beta * radius);
    const double rotation = moment / s.b.kben[0];
    const double t_fail = steps_to_fail * dt, w = 0.5 * rotation / t_fail;
    s.drive(Vec3::Zero(), Vec3(0, -w, 0), Vec3::Zero(), Vec3(0, w, 0));
    const auto r = run(s, dt, long(2 * steps_to_fail));
    ASSERT_GT(r.time, 0);
    EXPECT_NEAR(r.time, t_fail, 1e-3 * t_fail) << "beta " << beta;
    EXPECT_NEAR(r.moment.norm(), moment, 1e-3 * moment) << "beta " << beta;
    EXPECT_LT(r.force.norm(), 1e-6 * sigma_t * area);
    EXPECT_EQ(r.crack.mode, CrackMode::tension);
  }
}

// Pure torsion (opposite twists about the axis): tau = beta |M_t| R / J = tau_c at
// M_t = tau_c J / (beta R), the twist M_t / k_tor.
TEST_P(BondFailure, PureTorsion)
{
  const double tau_c = 1.5e6;
  BondedPair s(GetParam(), brittle(5e6, tau_c));
  const double moment = tau_c * polar / radius;
  const double twist = moment / s.b.ktor[0];
  const double t_fail = steps_to_fail * dt, w = 0.5 * twist / t_fail;
  s.drive(Vec3::Zero(), Vec3(-w, 0, 0), Vec3::Zero(), Vec3(w, 0, 0));
  const auto r = run(s, dt, long(2 * steps_to_fail));
  ASSERT_GT(r.time, 0);
  EXPECT_NEAR(r.time, t_fail, 1e-3 * t_fail);
  EXPECT_NEAR(std::abs(r.moment.x()), moment, 1e-3 * moment);
  EXPECT_EQ(r.crack.mode, CrackMode::shear);
}

INSTANTIATE_TEST_SUITE_P(AllModels, BondFailure,
                         ::testing::Values(BondModel::parallel_bond, BondModel::euler_bernoulli,
                                           BondModel::timoshenko),
                         [](const auto& info)
                         { return std::string(bond_model_names[int(info.param)]); });

// The stress formulas themselves, on a hand-made force and couple (tilted axis).
TEST(BondStress, BeamTheoryOnTheSection)
{
  const Vec3 e = Vec3(1, 2, 2) / 3.0, t1 = Vec3(2, -1, 0).normalized(), t2 = e.cross(t1);
  const double Fn = 300, Fs = 400, Mt = 2, Mb = 3, beta = 0.7;
  const Vec3 F = -Fn * e + Fs * t1, M = Mt * e + Mb * t2;
  const BondStress s = bond_stress(F.data(), M.data(), e.data(), radius, beta);
  EXPECT_NEAR(s.tensile, Fn / area + beta * Mb * radius / inertia, 1e-9 * s.tensile);
  EXPECT_NEAR(s.shear, Fs / area + beta * Mt * radius / polar, 1e-9 * s.shear);
  EXPECT_NEAR(s.normal_force, Fn, 1e-12 * Fn);
}

// Mohr-Coulomb: the bond first compressed to sigma_c (a short ramp), then sheared; it fails in
// shear at tau = c + sigma_c tan(phi), within 0.1 %, for three compressions.
TEST(BondFailureMohrCoulomb, ShearStrengthRisesWithCompression)
{
  const double c = 1e6, phi = 30.0;
  for (double sigma_c : {0.0, 1e6, 3e6})
  {
    DamageConfig d = brittle(5e6, 0);
    d.law.shear = ShearCriterion::mohr_coulomb;
    d.cohesion = c;
    d.friction_angle = phi;
    BondedPair s(BondModel::timoshenko, d);
    const double tau = c + sigma_c * std::tan(phi * std::numbers::pi / 180);
    const double t_fail = steps_to_fail * dt, v = tau * area / s.b.ks[0] / t_fail;
    const double squeeze = sigma_c * area / s.b.kn[0];
    s.loads.push_back({.name = "squeeze",
                       .group = 1,
                       .kind = LoadKind::displacement,
                       .value = Vec3(-squeeze, 0, 0),
                       .components = 1,
                       .ramp_time = 0.02 * t_fail});
    s.loads.push_back({.name = "shear",
                       .group = 1,
                       .kind = LoadKind::velocity,
                       .value = Vec3(0, v, 0),
                       .components = 6});
    s.loads.push_back({.name = "w", .group = 1, .kind = LoadKind::angular_velocity});
    s.loads.push_back({.name = "a", .group = 0, .kind = LoadKind::velocity});
    s.loads.push_back({.name = "wa", .group = 0, .kind = LoadKind::angular_velocity});
    const auto r = run(s, dt, long(2 * steps_to_fail));
    ASSERT_GT(r.time, 0);
    // in the bond's frame at failure; the shear displacement lengthens the chord a little, so
    // the compression at failure is a little below the one applied (0.3 % at 1 MPa)
    const Vec3 e = r.axis;
    const double compression = r.force.dot(e) / area;
    EXPECT_NEAR(compression, sigma_c, 0.01 * std::max(sigma_c, c));
    const double strength = c + std::max(0.0, compression) * std::tan(phi * std::numbers::pi / 180);
    EXPECT_NEAR((r.force - r.force.dot(e) * e).norm() / area, strength, 1e-3 * strength)
        << "sigma_c " << sigma_c;
    EXPECT_NEAR(strength, tau, 0.01 * tau);
    EXPECT_EQ(r.crack.mode, CrackMode::shear);
  }
}

// Brittle break, dynamic: b flies off a (held) with twice the kinetic energy the bond can
// store. The bond's energy at the break is booked as fracture: the balance closes to 1e-6
// through the break, and what is left is kinetic energy (initial - fracture).
TEST(BondFailureEnergy, BrittleBreakBooksTheStrainEnergy)
{
  for (BondModel m : {BondModel::parallel_bond, BondModel::timoshenko})
  {
    const double sigma_t = 1e6;
    BondedPair s(m, brittle(sigma_t, 5e6));
    const double peak = sigma_t * sigma_t * area * area / (2 * s.b.kn[0]);
    s.p.velocity[1] = Vec3(std::sqrt(2 * 2 * peak / s.p.mass[1]), 0, 0);
    s.loads.push_back({.name = "hold", .group = 0, .kind = LoadKind::velocity});
    s.loads.push_back({.name = "hold_w", .group = 0, .kind = LoadKind::angular_velocity});
    // a step 1/50 of the critical one: the break comes after about a hundred steps
    const double step = 0.02 * estimate_critical_time_step(s.p, s.b).critical();
    const auto r = run(s, step, 100000, 50);
    ASSERT_GT(r.time, 0);
    EXPECT_LT(r.worst_balance, 1e-6) << bond_model_names[int(m)];
    EXPECT_NEAR(r.energy.fracture, r.crack.energy, 1e-12 * peak);
    EXPECT_NEAR(r.energy.fracture, peak, 0.05 * peak); // at most a step past the peak
    EXPECT_NEAR(r.energy.kinetic, r.energy.initial - r.energy.fracture, 1e-6 * peak);
    EXPECT_EQ(r.energy.strain, 0.0);
  }
}

// A broken bond stays broken: the particles pushed back together (and past) carry no force,
// the bond's state stays broken and the pair is not re-bonded.
TEST(BondFailureEnergy, BrokenStaysBroken)
{
  const double sigma_t = 1e6;
  BondedPair s(BondModel::parallel_bond, brittle(sigma_t, 5e6));
  const double stretch = sigma_t * area / s.b.kn[0];
  const double t_fail = 1000 * dt, v = stretch / t_fail;
  // out for 1.5 t_fail, then back by three times as far
  s.loads.push_back({.name = "out",
                     .group = 1,
                     .kind = LoadKind::velocity,
                     .value = Vec3(v, 0, 0),
                     .end_time = 1.5 * t_fail});
  s.loads.push_back({.name = "a", .group = 0, .kind = LoadKind::velocity});
  ExplicitSolver solver(s.p, s.b, s.groups(), {}, s.loads, {dt, 0.0, 1});
  for (int n = 0; n < 1500; ++n)
    solver.step(true);
  ASSERT_EQ(s.b.state[0], BondState::broken);
  s.p.velocity[1] = Vec3(-3 * v, 0, 0);
  for (int n = 0; n < 1500; ++n)
  {
    solver.step(true);
    ASSERT_EQ(s.b.state[0], BondState::broken);
    ASSERT_EQ(s.p.force[1].norm(), 0.0);
  }
  EXPECT_LT(s.p.position[1].x() - s.p.position[0].x(), s.b.rest_length[0]); // pushed past
  EXPECT_EQ(solver.n_broken_bonds(), 1);
  EXPECT_EQ(s.p.coordination[1], 0);
}

// Softening to G_f (bond_damage.h eq. 3-4): the dissipated energy is G_f A within 1 %, in mode I
// (tension) and mode II (shear), for two time steps (4x apart) that agree within 0.1 %; the
// force peaks at the strength and falls linearly (half the peak force midway to kappa_u); the
// energy balance closes to 1e-6 through softening and the break (tension).
TEST(BondFailureSoftening, DissipatesTheFractureEnergy)
{
  const double sigma_t = 1e6, tau_c = 1.5e6;
  for (bool shear : {false, true})
  {
    double dissipated[2];
    for (int run_index = 0; run_index < 2; ++run_index)
    {
      DamageConfig d = brittle(shear ? 5e6 : sigma_t, shear ? tau_c : 5e6);
      d.law.mode = FailureMode::softening;
      BondedPair probe(BondModel::timoshenko, brittle(1, 1));
      // kappa_u = 6 in both modes: G_f = 6 U_peak / A
      d.law.fracture_energy_I =
          6 * d.tensile_strength * d.tensile_strength * area / (2 * probe.b.kn[0]);
      d.law.fracture_energy_II =
          6 * d.shear_strength * d.shear_strength * area / (2 * probe.b.ks[0]);
      const double k = shear ? probe.b.ks[0] : probe.b.kn[0];
      const double strength = shear ? tau_c : sigma_t;
      const double gf = shear ? d.law.fracture_energy_II : d.law.fracture_energy_I;
      BondedPair s(BondModel::timoshenko, d);
      const double peak_disp = strength * area / k;
      const double step = run_index == 0 ? dt : 4 * dt;
      const double v = peak_disp / (steps_to_fail * dt);
      s.drive(Vec3::Zero(), Vec3::Zero(), shear ? Vec3(0, v, 0) : Vec3(v, 0, 0), Vec3::Zero());
      ExplicitSolver solver(s.p, s.b, s.groups(), {}, s.loads, {step, 0.0, 1});
      double largest = 0, worst = 0, peak_force = 0, mid_force = -1;
      const double t_mid = 3.5 * peak_disp / v; // kappa = (1 + kappa_u) / 2
      while (s.b.state[0] != BondState::broken && solver.time() < 10 * peak_disp / v)
      {
        solver.step(true);
        largest = std::max(largest, solver.energy().largest());
        worst = std::max(worst, solver.energy().error() / largest);
        const Vec3 F = s.b.force[0];
        const double load = shear ? std::abs(F.y()) : -F.x();
        peak_force = std::max(peak_force, load);
        if (mid_force < 0 && solver.time() >= t_mid)
          mid_force = load;
      }
      ASSERT_EQ(s.b.state[0], BondState::broken);
      dissipated[run_index] = solver.energy().fracture;
      EXPECT_NEAR(solver.energy().fracture, gf * area, 0.01 * gf * area) << "shear " << shear;
      EXPECT_NEAR(solver.cracks().at(0).energy, solver.energy().fracture, 1e-12 * gf * area);
      EXPECT_EQ(solver.cracks()[0].mode, shear ? CrackMode::shear : CrackMode::tension);
      EXPECT_NEAR(peak_force, strength * area, 2e-3 * strength * area);
      EXPECT_NEAR(mid_force, 0.5 * strength * area, 5e-3 * strength * area);
      // Tension: to 1e-6. Shear: the chord turns by u/L (up to 1e-2 rad at kappa_u); the total
      // co-rotational law's forces and closed-form energy differ at second order in that angle,
      // so the error grows with u^2 from the first step on, before any damage (1.6e-6 at the
      // peak, 2.2e-5 at the break), and is the same for both time steps: 1e-4 there.
      EXPECT_LT(worst, shear ? 1e-4 : 1e-6) << "shear " << shear;
    }
    EXPECT_NEAR(dissipated[0], dissipated[1], 1e-3 * dissipated[0]) << "shear " << shear;
  }
}

// Strengths: same seed -> bit-identical, another seed -> different; normal scatter keeps its
// mean and relative std dev and stays positive; Weibull keeps the mean and has the coefficient
// of variation sqrt(Gamma(1 + 2/m) / Gamma(1 + 1/m)^2 - 1).
TEST(BondStrength, SeededScatter)
{
  const std::size_t n = 40000;
  auto store = [&]
  {
    BondStore b;
    BondStiffness k;
    k.kn = 1e7, k.ks = 1e7, k.radius = 0.01;
    for (std::size_t i = 0; i < n; ++i)
      b.add(0, 1, 0.02, Vec3::UnitX(), BondModel::parallel_bond, k);
    return b;
  };
  auto stats = [](const std::vector<double>& v)
  {
    double mean = 0, var = 0, low = v[0];
    for (double x : v)
      mean += x, low = std::min(low, x);
    mean /= double(v.size());
    for (double x : v)
      var += (x - mean) * (x - mean);
    return std::tuple{mean, std::sqrt(var / double(v.size() - 1)), low};
  };
  DamageConfig d = brittle(1e6, 2e6);
  d.scatter = StrengthScatter::normal;
  d.scatter_deviation = 0.4;
  d.seed = 7;
  BondStore b1 = store(), b2 = store(), b3 = store();
  assign_bond_strengths(b1, d);
  assign_bond_strengths(b2, d);
  d.seed = 8;
  assign_bond_strengths(b3, d);
  EXPECT_EQ(b1.tensile_strength, b2.tensile_strength);
  EXPECT_EQ(b1.shear_strength, b2.shear_strength);
  EXPECT_NE(b1.tensile_strength, b3.tensile_strength);
  const auto [mean, dev, low] = stats(b1.tensile_strength);
  // truncation at 0 (2.5 sigma) shifts the mean by 0.4 * 0.018 = 0.7 %
  EXPECT_NEAR(mean, 1e6, 0.015e6);
  EXPECT_NEAR(dev / mean, 0.4, 0.02);
  EXPECT_GT(low, 0);

  d.scatter = StrengthScatter::weibull;
  d.weibull_modulus = 5;
  BondStore w = store();
  assign_bond_strengths(w, d);
  const auto [wmean, wdev, wlow] = stats(w.shear_strength);
  const double g1 = std::tgamma(1.2), g2 = std::tgamma(1.4);
  EXPECT_NEAR(wmean, 2e6, 0.01 * 2e6);
  EXPECT_NEAR(wdev / wmean, std::sqrt(g2 / (g1 * g1) - 1), 0.01);
  EXPECT_GT(wlow, 0);
}

namespace
{
std::string error_of(BondStore b, const DamageConfig& d)
{
  try
  {
    assign_bond_strengths(b, d);
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

// Bad input: one-line errors naming Damage/key.
TEST(BondStrength, RefusesBadInput)
{
  BondedPair s(BondModel::timoshenko, {});
  auto expect = [&](const DamageConfig& d, const std::string& text)
  {
    const std::string e = error_of(s.b, d);
    EXPECT_NE(e.find(text), std::string::npos) << "got '" << e << "', expected '" << text << "'";
    EXPECT_EQ(e.find('\n'), std::string::npos);
  };
  expect(brittle(0, 1e6), "Damage/tensile strength: must be positive");
  expect(brittle(-1e6, 1e6), "Damage/tensile strength: must be positive");
  expect(brittle(1e6, 0), "Damage/shear strength: must be positive");
  DamageConfig mc = brittle(1e6, 0);
  mc.law.shear = ShearCriterion::mohr_coulomb;
  expect(mc, "Damage/cohesion: must be positive");
  mc.cohesion = 1e6;
  mc.friction_angle = 90;
  expect(mc, "Damage/friction angle");
  expect(brittle(1e6, 1e6, 1.5), "Damage/moment factor");
  DamageConfig soft = brittle(1e6, 1e6);
  soft.law.mode = FailureMode::softening;
  expect(soft, "Damage/fracture energy mode I: softening needs a positive fracture energy");
  // snap-back: G_f A below sigma_t^2 A^2 / (2 k_n), resp. tau^2 A^2 / (2 k_s)
  const double need_I = 1e12 * area / (2 * s.b.kn[0]), need_II = 1e12 * area / (2 * s.b.ks[0]);
  soft.law.fracture_energy_I = 0.99 * need_I;
  soft.law.fracture_energy_II = 1.01 * need_II;
  expect(soft, "Damage/fracture energy mode I");
  expect(soft, "snap-back");
  soft.law.fracture_energy_I = 1.01 * need_I;
  EXPECT_EQ(error_of(s.b, soft), "");
  soft.law.fracture_energy_II = 0.99 * need_II;
  expect(soft, "Damage/fracture energy mode II");
}

// Threads: the bond loop with failure, run on two threads (bonds partitioned into slabs, failures
// logged per range and drained in particle-id order), breaks the same bonds in the same order as
// one thread, with the same energies to round-off: an HCP bar pulled apart along x.
TEST(BondFailureThreads, TwoThreadsBreakTheSameBonds)
{
  struct Bar
  {
    ParticleStore p;
    BondStore b;
    std::vector<Group> groups;
    std::vector<Load> loads;
    Bar()
    {
      ParticleSource src;
      src.kind = ParticleSource::Kind::hcp;
      src.radius = 5e-3;
      src.box_size = Vec3(0.1, 0.03, 0.03);
      generate_particles(src, p);
      BondMaterial mat;
      mat.youngs_modulus = 4e9;
      form_bonds(p, b, mat, 1.0);
      DamageConfig d = brittle(1e6, 2e6);
      d.scatter = StrengthScatter::normal;
      d.scatter_deviation = 0.3;
      assign_bond_strengths(b, d);
      Group left{"left", {}}, right{"right", {}};
      for (std::size_t i = 0; i < p.size(); ++i)
        (p.position[i].x() < 0.01 ? left : right).members.push_back(int(i));
      std::erase_if(right.members, [&](int i) { return p.position[i].x() < 0.09; });
      groups = {left, right};
      loads.push_back({.name = "hold", .group = 0, .kind = LoadKind::velocity, .components = 1});
      loads.push_back({.name = "pull",
                       .group = 1,
                       .kind = LoadKind::velocity,
                       .value = Vec3(0.05, 0, 0),
                       .components = 1});
    }
  };
  Bar one, two;
  const double dt = 0.5 * estimate_critical_time_step(one.p, one.b).critical();
  ExplicitSolver s1(one.p, one.b, one.groups, {}, one.loads, {dt, 0.3, 1});
  ExplicitSolver s2(two.p, two.b, two.groups, {}, two.loads, {dt, 0.3, 2});
  for (int n = 0; n < 600; ++n)
  {
    s1.step(n % 100 == 0);
    s2.step(n % 100 == 0);
  }
  ASSERT_GE(s1.n_broken_bonds(), 10);
  ASSERT_EQ(s1.n_broken_bonds(), s2.n_broken_bonds());
  for (long k = 0; k < s1.n_broken_bonds(); ++k)
  {
    const auto &c1 = s1.cracks()[k], &c2 = s2.cracks()[k];
    EXPECT_EQ(std::pair(c1.a, c1.b), std::pair(c2.a, c2.b)) << "crack " << k;
    EXPECT_EQ(c1.time, c2.time) << "crack " << k;
    EXPECT_NEAR(c1.energy, c2.energy, 1e-9 * c1.energy) << "crack " << k;
  }
  EXPECT_NEAR(s1.energy().fracture, s2.energy().fracture, 1e-9 * s1.energy().fracture);
  for (std::size_t i = 0; i < one.p.size(); ++i)
    EXPECT_EQ(one.p.coordination[i], two.p.coordination[i]);
}
