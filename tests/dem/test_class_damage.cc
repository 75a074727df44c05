// Per-class failure constants (bond_damage.h FailureConstants; microstructure.h BondClassConfig):
// a bond class's own friction angle, moment factor and fracture energies, read by the explicit
// solver's bond loop through the bond's class. One bond between two touching spheres (r =
// 10 mm, Timoshenko, 4 GPa), its class set as the microstructure sets it, its constants from the
// class's section (bond_class_configs, class_damage, assign_bond_strengths), driven kinematically:
//  - softening (bond_damage.h eq. 3-4): a bond dissipates its own class's G_f A, in mode I and
//    mode II, where the Damage values are 2.5 times smaller;
//  - Mohr-Coulomb (eq. 2): a bond compressed to sigma_c and sheared fails at
//    c + sigma_c tan(phi) with its class's phi;
//  - the moment factor (bond_stress.h): in pure bending a bond fails at
//    M = sigma_t I / (beta R) with its class's beta;
//  - bad class values: one line naming Bond class NAME/key.
#include "dem/bonds/bonding.h"
#include "dem/microstructure/microstructure.h"
#include "dem/packing/packings.h"
#include "dem/solvers/explicit_solver.h"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
constexpr double radius = 0.01;                             // particles and bond, m
constexpr double area = std::numbers::pi * radius * radius; // A
constexpr double inertia = 0.25 * area * radius * radius;   // I = pi R^4 / 4
constexpr double dt = 1e-6;                                 // kinematic runs: any step is stable
constexpr double steps_to_fail = 2e4;
constexpr double deg = std::numbers::pi / 180;

BondMaterial material()
{
  BondMaterial m;
  m.model = BondModel::timoshenko;
  m.youngs_modulus = 4e9;
  m.poisson_ratio = 0.3;
  return m;
}

/// Two touching spheres along x joined by one bond of class @p cls, whose constants are the
/// weak-plane section @p weak (the other classes: Damage's) as a case's microstructure gives
/// them.
struct ClassedPair
{
  ParticleStore p;
  BondStore b;
  std::vector<Load> loads;
  ClassedPair(BondClass cls, const DamageConfig& damage, const BondClassConfig& weak)
  {
    ParticleSource src;
    src.kind = ParticleSource::Kind::row;
    src.count = 2;
    src.radius = radius;
    src.density = 1000;
    generate_particles(src, p);
    add_bond(p, b, material(), 0, 1);
    mark_reference_configuration(p);
    b.bond_class = {cls};
    MicrostructureConfig config;
    config.weak_plane = weak;
    const auto classes = bond_class_configs(config, material(), damage);
    const auto damages = class_damage(classes, damage);
    assign_bond_strengths(b, damage, nullptr, damages);
  }
  /// Particle a held, b moved with velocity @p v and angular velocity @p w; a turned by -w.
  void drive(const Vec3& v, const Vec3& w)
  {
    loads.push_back({.name = "va", .group = 0, .kind = LoadKind::velocity});
    loads.push_back({.name = "wa", .group = 0, .kind = LoadKind::angular_velocity, .value = -w});
    loads.push_back({.name = "vb", .group = 1, .kind = LoadKind::velocity, .value = v});
    loads.push_back({.name = "wb", .group = 1, .kind = LoadKind::angular_velocity, .value = w});
  }
  std::vector<Group> groups() const { return {{"a", {0}}, {"b", {1}}}; }
};

/// Runs until the bond breaks (at most @p max_steps); the force and couple on b and the chord
/// at the last step before the break, and the solver's fracture energy.
struct Broken
{
  bool broke = false;
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
  Vec3 axis = Vec3::UnitX(); ///< the bond's chord a -> b at that step
  double fracture = 0;
  CrackMode mode = CrackMode::tension;
};

Broken run_until_broken(ClassedPair& s, long max_steps)
{
  ExplicitSolver solver(s.p, s.b, s.groups(), {}, s.loads, {dt, 0.0, 1});
  Broken r;
  for (long n = 0; n < max_steps && s.b.state[0] != BondState::broken; ++n)
  {
    r.force = s.b.force[0], r.moment = s.b.moment[0];
    r.axis = (s.p.position[1] - s.p.position[0]).normalized();
    solver.step(true);
  }
  r.broke = s.b.state[0] == BondState::broken;
  r.fracture = solver.energy().fracture;
  if (r.broke)
    r.mode = solver.cracks().at(0).mode;
  return r;
}

DamageConfig brittle(double sigma_t, double tau_c)
{
  DamageConfig d;
  d.law.mode = FailureMode::brittle;
  d.tensile_strength = sigma_t;
  d.shear_strength = tau_c;
  return d;
}
} // namespace

// Softening: each bond dissipates its class's G_f A (kappa_u = 15 for the weak-plane class, 6
// for Damage's), in tension (mode I) and shear (mode II), within 0.1 % (as
// BondFailureSoftening.DissipatesTheFractureEnergy holds a specimen's own G_f to 1 %).
TEST(ClassDamage, SofteningBondDissipatesItsClassFractureEnergy)
{
  const double sigma_t = 1e6, tau_c = 1.5e6;
  ClassedPair probe(BondClass::intra_grain, brittle(1, 1),
                    BondClassConfig::of_specimen(material(), brittle(1, 1)));
  const double kn = probe.b.kn[0], ks = probe.b.ks[0];
  for (bool shear : {false, true})
  {
    DamageConfig d = brittle(shear ? 5e6 : sigma_t, shear ? tau_c : 5e6);
    d.law.mode = FailureMode::softening;
    d.law.fracture_energy_I = 6 * d.tensile_strength * d.tensile_strength * area / (2 * kn);
    d.law.fracture_energy_II = 6 * d.shear_strength * d.shear_strength * area / (2 * ks);
    BondClassConfig weak = BondClassConfig::of_specimen(material(), d);
    weak.fracture_energy_I = 2.5 * d.law.fracture_energy_I;
    weak.fracture_energy_II = 2.5 * d.law.fracture_energy_II;
    const double strength = shear ? tau_c : sigma_t, k = shear ? ks : kn;
    const double peak_disp = strength * area / k, v = peak_disp / (steps_to_fail * dt);
    for (BondClass cls : {BondClass::weak_plane, BondClass::intra_grain})
    {
      ClassedPair s(cls, d, weak);
      s.drive(shear ? Vec3(0, v, 0) : Vec3(v, 0, 0), Vec3::Zero());
      const Broken r = run_until_broken(s, long(20 * steps_to_fail));
      ASSERT_TRUE(r.broke);
      const BondClassConfig& own =
          cls == BondClass::weak_plane ? weak : BondClassConfig::of_specimen(material(), d);
      const double gf = shear ? own.fracture_energy_II : own.fracture_energy_I;
      std::printf("%s, %s: dissipated %.6e J, G_f A %.6e J (ratio %.5f)\n",
                  shear ? "mode II" : "mode I", std::string(bond_class_name(cls)).c_str(),
                  r.fracture, gf * area, r.fracture / (gf * area));
      EXPECT_NEAR(r.fracture, gf * area, 1e-3 * gf * area) << bond_class_name(cls);
      EXPECT_EQ(r.mode, shear ? CrackMode::shear : CrackMode::tension);
    }
  }
}

// Mohr-Coulomb: compressed to sigma_c, then sheared, a bond fails in shear at
// tau = c + sigma_c tan(phi) with its class's phi (50 degrees; Damage's 30), within 0.1 %.
TEST(ClassDamage, FrictionAngleSetsTheClassEnvelope)
{
  const double c = 1e6, sigma_c = 2e6;
  DamageConfig d = brittle(5e6, 0);
  d.law.shear = ShearCriterion::mohr_coulomb;
  d.cohesion = c;
  d.friction_angle = 30;
  BondClassConfig weak = BondClassConfig::of_specimen(material(), d);
  weak.friction_angle = 50;
  for (BondClass cls : {BondClass::weak_plane, BondClass::intra_grain})
  {
    const double phi = cls == BondClass::weak_plane ? 50 : 30;
    const double tau = c + sigma_c * std::tan(phi * deg);
    ClassedPair s(cls, d, weak);
    const double t_fail = steps_to_fail * dt, v = tau * area / s.b.ks[0] / t_fail;
    const double squeeze = sigma_c * area / s.b.kn[0];
    s.loads = {{.name = "squeeze",
                .group = 1,
                .kind = LoadKind::displacement,
                .value = Vec3(-squeeze, 0, 0),
                .components = 1,
                .ramp_time = 0.02 * t_fail},
               {.name = "shear",
                .group = 1,
                .kind = LoadKind::velocity,
                .value = Vec3(0, v, 0),
                .components = 6},
               {.name = "wb", .group = 1, .kind = LoadKind::angular_velocity},
               {.name = "va", .group = 0, .kind = LoadKind::velocity},
               {.name = "wa", .group = 0, .kind = LoadKind::angular_velocity}};
    const Broken r = run_until_broken(s, long(2 * steps_to_fail));
    ASSERT_TRUE(r.broke);
    const Vec3 e = r.axis; // the section's normal: the shear turns the chord a little
    const double compression = r.force.dot(e) / area;
    const double strength = c + compression * std::tan(phi * deg);
    const double sheared = (r.force - r.force.dot(e) * e).norm() / area;
    std::printf("%s: sigma_c %.4f MPa, fails at tau %.5f MPa, c + sigma_c tan %.0f = %.5f MPa\n",
                std::string(bond_class_name(cls)).c_str(), compression / 1e6, sheared / 1e6, phi,
                strength / 1e6);
    // the shear at failure lengthens the chord a little: 1.3 % less compression at 50 degrees
    EXPECT_NEAR(compression, sigma_c, 0.02 * sigma_c);
    EXPECT_NEAR(sheared, strength, 1e-3 * strength) << bond_class_name(cls);
    EXPECT_EQ(r.mode, CrackMode::shear);
  }
}

// Moment factor: rotated opposite ways about y (pure bending), a bond fails at
// M = sigma_t I / (beta R) with its class's beta (0.5; Damage's 1), within 0.2 %.
TEST(ClassDamage, MomentFactorSetsTheClassBendingStrength)
{
  const double sigma_t = 1e6;
  const DamageConfig d = brittle(sigma_t, 1e9);
  BondClassConfig weak = BondClassConfig::of_specimen(material(), d);
  weak.moment_factor = 0.5;
  for (BondClass cls : {BondClass::weak_plane, BondClass::intra_grain})
  {
    const double beta = cls == BondClass::weak_plane ? 0.5 : 1.0;
    const double moment = sigma_t * inertia / (beta * radius);
    ClassedPair s(cls, d, weak);
    const double w = 0.5 * moment / s.b.kben[0] / (steps_to_fail * dt);
    s.drive(Vec3::Zero(), Vec3(0, w, 0));
    const Broken r = run_until_broken(s, long(2 * steps_to_fail));
    ASSERT_TRUE(r.broke);
    std::printf("%s: fails at M %.6f N m, sigma_t I / (beta R) = %.6f N m\n",
                std::string(bond_class_name(cls)).c_str(), r.moment.norm(), moment);
    EXPECT_NEAR(r.moment.norm(), moment, 2e-3 * moment) << bond_class_name(cls);
    EXPECT_EQ(r.mode, CrackMode::tension);
  }
}

namespace
{
std::string error_of(const DamageConfig& d, const BondClassConfig& weak)
{
  try
  {
    ClassedPair s(BondClass::weak_plane, d, weak);
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

// Bad class values: one line naming the class's section and key.
TEST(ClassDamage, RefusesBadClassValues)
{
  auto expect = [&](const DamageConfig& d, const BondClassConfig& weak, const std::string& text)
  {
    const std::string e = error_of(d, weak);
    EXPECT_NE(e.find(text), std::string::npos) << "got '" << e << "', expected '" << text << "'";
    EXPECT_EQ(e.find('\n'), std::string::npos);
  };
  DamageConfig mc = brittle(1e6, 0);
  mc.law.shear = ShearCriterion::mohr_coulomb;
  mc.cohesion = 1e6;
  mc.friction_angle = 30;
  BondClassConfig weak = BondClassConfig::of_specimen(material(), mc);
  weak.friction_angle = 90;
  expect(mc, weak, "Bond class weak_plane/friction angle: must lie in [0, 90) degrees (got 90)");
  weak.friction_angle = -5;
  expect(mc, weak, "Bond class weak_plane/friction angle: must lie in [0, 90) degrees (got -5)");
  weak = BondClassConfig::of_specimen(material(), mc);
  weak.moment_factor = 1.5;
  expect(mc, weak, "Bond class weak_plane/moment factor: must lie in [0, 1] (got 1.5)");
  // softening: a class without fracture energy, and one below its bonds' peak energy
  DamageConfig soft = brittle(1e6, 1e6);
  soft.law.mode = FailureMode::softening;
  soft.law.fracture_energy_I = soft.law.fracture_energy_II = 1e3;
  weak = BondClassConfig::of_specimen(material(), soft);
  weak.fracture_energy_II = 0;
  expect(soft, weak,
         "Bond class weak_plane/fracture energy mode II: softening needs a positive fracture "
         "energy, J/m^2 (got 0)");
  weak = BondClassConfig::of_specimen(material(), soft);
  EXPECT_EQ(error_of(soft, weak), "");
  weak.fracture_energy_I = 1e-6;
  expect(soft, weak, "Bond class weak_plane/fracture energy mode I: 1e-06 J/m^2 is below");
  expect(soft, weak, "(a weak_plane bond) (snap-back)");
}
