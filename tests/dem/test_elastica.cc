// Large deflection of a cantilever (the elastica) by the explicit solver. A clamped chain of
// Euler-Bernoulli bonds (bending stiffness E I of the bond section, no shear deformation) under a
// tip load P of fixed direction, run to rest with local damping: the explicit solver's law is
// co-rotational (exact under large rotations), so the chain follows the elastica, not the linear
// beam (P L^3 / 3 E I).
//
// The elastica of an inextensible cantilever (Bisshopp & Drucker 1945; Timoshenko & Gere,
// Theory of Elastic Stability, 1961, section 2.7), alpha = P L^2 / (E I), tip angle theta_0:
//   sqrt(alpha) = K(k) - F(k, phi_1),   k^2 = (1 + sin theta_0) / 2,   sin phi_1 = 1 / (k sqrt 2),
//   tip deflection      delta_v / L = 1 - 2 (E(k) - E(k, phi_1)) / sqrt(alpha),
//   horizontal shortening  delta_h / L = 1 - sqrt(2 sin theta_0 / alpha),
// with F, E the incomplete elliptic integrals of the first and second kind (std::ellint_1,
// std::ellint_2) and K, E their complete forms. The closed form is checked against a shooting
// solution of the elastica's equation theta'' = -alpha cos theta (s in [0, 1], theta(0) = 0,
// theta'(1) = 0) to 1e-8.
//
// alpha = 1 gives a tip deflection of 30 % of the length (the linear beam: 33 %). Checked at 20
// and 40 bonds: deflection and shortening within 0.5 % of the elastica, and the larger of the
// two errors smaller at 40 bonds than at 20 (measured: deflection +0.006 % and +0.003 %,
// shortening -0.057 % and -0.023 %; what remains at 40 bonds is mostly the bonds' extension,
// which the inextensible elastica lacks: the axial force is at most P and P / E A = r_b^2 /
// (4 L^2) = 2.5e-5, 4e-4 of the shortening).
#include "dem/solvers/run_explicit.h"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
constexpr double pi = std::numbers::pi;
constexpr double length = 1.0, bond_radius = 0.01, youngs = 200e9, alpha = 1.0;

double bending_stiffness()
{
  return youngs * 0.25 * pi * std::pow(bond_radius, 4); // E I
}

struct Elastica
{
  double tip_angle, deflection, shortening; ///< rad; both over L
};

/// The closed form by elliptic integrals; the tip angle by bisection on sqrt(alpha).
Elastica closed_form(double a)
{
  auto terms = [](double theta0, double& k, double& phi1)
  {
    k = std::sqrt(0.5 * (1 + std::sin(theta0)));
    phi1 = std::asin(1 / (k * std::sqrt(2.0)));
  };
  double lo = 1e-9, hi = 0.5 * pi - 1e-12;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    double k, phi1;
    terms(mid, k, phi1);
    // the length this tip angle needs grows with the angle
    (std::comp_ellint_1(k) - std::ellint_1(k, phi1) < std::sqrt(a) ? lo : hi) = mid;
  }
  const double theta0 = 0.5 * (lo + hi);
  double k, phi1;
  terms(theta0, k, phi1);
  return {theta0, 1 - 2 * (std::comp_ellint_2(k) - std::ellint_2(k, phi1)) / std::sqrt(a),
          1 - std::sqrt(2 * std::sin(theta0) / a)};
}

/// Shooting: theta'' = -a cos(theta) by RK4 from theta(0) = 0, theta'(0) = c, with x' = cos,
/// y' = sin; c by bisection so that theta'(1) = 0.
Elastica shooting(double a)
{
  auto integrate = [a](double c, Elastica& out)
  {
    const int n = 20000;
    const double h = 1.0 / n;
    double y[4] = {0, c, 0, 0}; // theta, theta', x, y
    auto f = [a](const double* s, double* d)
    {
      d[0] = s[1];
      d[1] = -a * std::cos(s[0]);
      d[2] = std::cos(s[0]);
      d[3] = std::sin(s[0]);
    };
    for (int i = 0; i < n; ++i)
    {
      double k1[4], k2[4], k3[4], k4[4], t[4];
      f(y, k1);
      for (int j = 0; j < 4; ++j)
        t[j] = y[j] + 0.5 * h * k1[j];
      f(t, k2);
      for (int j = 0; j < 4; ++j)
        t[j] = y[j] + 0.5 * h * k2[j];
      f(t, k3);
      for (int j = 0; j < 4; ++j)
        t[j] = y[j] + h * k3[j];
      f(t, k4);
      for (int j = 0; j < 4; ++j)
        y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    }
    out = {y[0], y[3], 1 - y[2]};
    return y[1]; // theta'(1)
  };
  double lo = 0, hi = 2 * a + 2; // theta'(1) falls as theta'(0) falls
  Elastica out{};
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (integrate(mid, out) > 0 ? hi : lo) = mid;
  }
  integrate(0.5 * (lo + hi), out);
  return out;
}

/// A cantilever of `bonds` Euler-Bernoulli bonds along x (touching spheres, the bond radius
/// 10 mm at every resolution), particle 0 clamped, the tip load P = alpha E I / L^2 along -z
/// ramped over 1 s, local damping 0.7, run until the unbalanced-force ratio falls below 1e-7
/// (1e-8 moves the tip by less than 1e-6 of its displacement).
struct ChainResult
{
  double deflection, shortening; ///< over L
  std::string stop_reason;
  double energy_balance_error;
};
ChainResult chain(int bonds)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::row;
  c.particles.count = bonds + 1;
  const double spacing = length / bonds;
  c.particles.radius = 0.5 * spacing;
  c.particles.spacing = spacing;
  c.particles.density = 7850;
  c.bonds.material.model = BondModel::euler_bernoulli;
  c.bonds.material.youngs_modulus = youngs;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.material.radius_multiplier = bond_radius / c.particles.radius;
  for (int i = 0; i < bonds; ++i)
    c.bonds.explicit_bonds.push_back({i, i + 1});
  GroupConfig clamp{"clamp", {}, 63, 0, Vec3::Zero()}, tip{"tip", {}, 0, 0, Vec3::Zero()};
  clamp.selection.kind = tip.selection.kind = GroupSelection::Kind::index;
  clamp.selection.indices = {0};
  tip.selection.indices = {-1};
  c.groups = {clamp, tip};
  LoadConfig load;
  load.group = "tip";
  load.load.name = "tip_load";
  load.load.value = Vec3(0, 0, -alpha * bending_stiffness() / (length * length));
  load.load.ramp_time = 1.0;
  c.loads = {load};
  c.run.particle_damping = 0.7;
  c.run.end_time = 100;
  c.run.equilibrium_ratio = 1e-7;
  c.measure.deflection_group = "tip";
  c.measure.deflection_name = "tip_deflection";
  Model model = build_model(c);
  RunObserver quiet;
  const RunResult r = run_explicit(model, c, quiet, {});
  const Vec3 u = r.deflection_vector;
  std::printf("%d bonds: %ld steps, stop %s, tip displacement (%.9f, %.9f, %.9f) m, energy "
              "balance %.1e\n",
              bonds, r.steps, r.stop_reason.c_str(), u.x(), u.y(), u.z(), r.energy_balance_error);
  return {-u.z() / length, -u.x() / length, r.stop_reason, r.energy_balance_error};
}
} // namespace

TEST(Elastica, ClosedFormEqualsShooting)
{
  const Elastica e = closed_form(alpha), s = shooting(alpha);
  std::printf("alpha = %g: tip angle %.10f rad, deflection %.10f L, shortening %.10f L (closed "
              "form); shooting %.10f, %.10f, %.10f\n",
              alpha, e.tip_angle, e.deflection, e.shortening, s.tip_angle, s.deflection,
              s.shortening);
  EXPECT_NEAR(e.tip_angle, s.tip_angle, 1e-8);
  EXPECT_NEAR(e.deflection, s.deflection, 1e-8);
  EXPECT_NEAR(e.shortening, s.shortening, 1e-8);
  // large: 30 % deflection, 10 % below the linear beam's alpha / 3
  EXPECT_GT(e.deflection, 0.29);
  EXPECT_LT(e.deflection, 0.31);
}

TEST(Elastica, ExplicitSolverFollowsTheElastica)
{
  const Elastica exact = closed_form(alpha);
  double previous = 1;
  for (const int bonds : {20, 40})
  {
    const ChainResult r = chain(bonds);
    const double dv = r.deflection / exact.deflection - 1, dh = r.shortening / exact.shortening - 1;
    std::printf("%d bonds: deflection %.7f L (elastica %.7f, %+.3f %%; linear beam %.4f), "
                "shortening %.7f L (elastica %.7f, %+.3f %%)\n",
                bonds, r.deflection, exact.deflection, 100 * dv, alpha / 3, r.shortening,
                exact.shortening, 100 * dh);
    EXPECT_EQ(r.stop_reason, "equilibrium") << bonds;
    EXPECT_NEAR(dv, 0, 5e-3) << bonds;
    EXPECT_NEAR(dh, 0, 5e-3) << bonds;
    EXPECT_LT(r.energy_balance_error, 0.01) << bonds;
    const double error = std::max(std::abs(dv), std::abs(dh));
    EXPECT_LT(error, previous) << bonds; // converges with the resolution
    previous = error;
  }
}
