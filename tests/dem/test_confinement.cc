// Confinement by a pressure on a side face (dem/model/loads.h): a fixed confining stress and a
// stress held in proportion to the axial one (sigma_2 = R sigma_1, Smith & Schulson's biaxial
// loading), checked on an elastic HCP block:
//  - the explicit solver's servo against the exact linear answer: the static solver is linear,
//    so with the axial drive u alone (state A) and a unit pressure alone (state B) the pressure
//    that is R times the axial stress is p* = R sigma_A / (1 - R sigma_B); the static state with
//    p* (state C) is where the servo-loaded explicit run must settle;
//  - the continuum's closed form: under sigma_1 along x and sigma_2 = R sigma_1 along y (z free),
//    eps_1 = (sigma_1 - nu_xy sigma_2) / E_x, so the apparent modulus sigma_1 / eps_1 is
//    E_x / (1 - nu_xy R), with E_x and nu_xy from the uniaxial state A.
#include "dem/measurements/crack_orientation.h"
#include "dem/measurements/measurements.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/static_solver.h"
#include "face_group.h"
#include <gtest/gtest.h>
#include <numbers>
#include <random>

using namespace dembridge::dem;

namespace
{
const Vec3 box(0.06, 0.05, 0.04);
constexpr double shortening = 2e-6; // m, the x+ face's push

using dembridge::test::face_group;

/// HCP block (r = 5 mm, parallel bonds): rollers on x-, y-, z- (symmetry planes), the x+ face
/// pushed along -x by `push` (its lateral motion free), the y+ face under the pressure p_0 +
/// R sigma_1 along -y, the z+ face free.
CaseConfig block_case(double push, double p0, double ratio, bool static_solver)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::hcp;
  c.particles.radius = 5e-3;
  c.particles.box_size = box;
  c.particles.density = 2500;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.material.stiffness_ratio = 2.5;
  c.groups = {face_group("x-", 0, false, dof_ux), face_group("y-", 1, false, dof_uy),
              face_group("z-", 2, false, dof_uz), face_group("x+", 0, true, 0),
              face_group("y+", 1, true, 0)};
  c.run.static_solver = static_solver;
  LoadConfig drive;
  drive.group = "x+";
  drive.load.name = "drive";
  drive.load.kind = LoadKind::displacement;
  drive.load.components = 1;
  drive.load.value = Vec3(-push, 0, 0);
  drive.load.profile = RampProfile::smooth;
  drive.load.ramp_time = static_solver ? 0.0 : 4e-3;
  drive.load.area = box.y() * box.z();
  LoadConfig confine;
  confine.group = "y+";
  confine.load.name = "confine";
  confine.load.kind = LoadKind::pressure;
  confine.load.value = Vec3(0, -1, 0);
  confine.load.area = box.x() * box.z();
  confine.load.pressure = p0;
  confine.load.ratio = ratio;
  if (ratio != 0)
    confine.ratio_load = "drive";
  c.loads = {drive, confine};
  return c;
}

struct State
{
  double sigma_x = 0;    ///< Pa, compression positive: the x+ face's reaction over its area
  double strain_x = 0;   ///< shortening over the gauge length
  double poisson_xy = 0; ///< nu_xy of the faces (measurements.h)
  Vec3 y_face_u;         ///< mean displacement of the y+ face
  double pressure = 0;   ///< Pa, applied on y+
};

State measure(const Model& m, double pressure)
{
  const AxialResponse a = axial_response(m.particles, m.groups[0], m.groups[3], 0);
  State s;
  s.sigma_x = -a.force / (box.y() * box.z());
  s.strain_x = -a.strain;
  s.poisson_xy = a.poisson_ratio[1];
  s.y_face_u = mean_displacement(m.particles, m.groups[4]);
  s.pressure = pressure;
  return s;
}

State static_state(double push, double p0)
{
  Model m = build_model(block_case(push, p0, 0, true));
  solve_static(m);
  return measure(m, p0);
}

/// The explicit run with the servo: the smooth ramp, then held until the unbalanced-force
/// ratio is below 1e-7 (mass damping).
State explicit_state(double ratio, double p0, double* final_ratio = nullptr)
{
  Model m = build_model(block_case(shortening, p0, ratio, false));
  ExplicitSolver s(m.particles, m.bonds, m.groups, m.constraints, m.loads,
                   {m.time_step, 0.0, 1, 2e4});
  while (s.time() < 4e-3)
    s.step();
  for (int k = 0; k < 200000; ++k)
  {
    s.step(k % 100 == 0);
    if (k % 100 == 0 && s.unbalanced_force_ratio() < 1e-7)
      break;
  }
  if (final_ratio)
    *final_ratio = s.applied_pressure(1) / s.reference_stress(0);
  EXPECT_LT(s.unbalanced_force_ratio(), 1e-7);
  EXPECT_LT(s.energy().relative_error(), 1e-3);
  return measure(m, s.applied_pressure(1));
}
} // namespace

// A fixed confining stress: the static and explicit solvers push the face alike, and the face
// moves by the superposition of the drive and the pressure's own response.
TEST(Confinement, FixedPressureIsLinearSuperposition)
{
  const double p0 = 2e5;
  const State a = static_state(shortening, 0), b = static_state(0, p0),
              both = static_state(shortening, p0);
  EXPECT_NEAR(both.y_face_u.y(), a.y_face_u.y() + b.y_face_u.y(),
              1e-9 * std::abs(both.y_face_u.y()));
  EXPECT_NEAR(both.sigma_x, a.sigma_x + b.sigma_x, 1e-9 * std::abs(both.sigma_x));
  // the pressure shortens the face's width: it pushes
  EXPECT_LT(b.y_face_u.y(), 0.0);
  const State e = explicit_state(0, p0);
  std::printf("p_0 = %.0f Pa: explicit against static: sigma_x %.2e, y+ face %.2e\n", p0,
              e.sigma_x / both.sigma_x - 1, e.y_face_u.y() / both.y_face_u.y() - 1);
  EXPECT_NEAR(e.pressure, p0, 1e-12 * p0);
  EXPECT_NEAR(e.sigma_x / both.sigma_x, 1.0, 2e-4);
  EXPECT_NEAR(e.y_face_u.y() / both.y_face_u.y(), 1.0, 2e-4);
}

// The servo holds sigma_2 = R sigma_1: the explicit run settles where linearity puts it, and the
// apparent modulus follows the continuum's E_x / (1 - nu_xy R).
TEST(Confinement, ProportionalPressureHoldsTheRatio)
{
  const State a = static_state(shortening, 0);
  const State unit = static_state(0, 1.0); // sigma_x per pascal of pressure (state B)
  const double e_x = a.sigma_x / a.strain_x, nu_xy = a.poisson_xy;
  EXPECT_GT(nu_xy, 0.05); // the closed form below has something to show
  for (double ratio : {0.3, 0.5})
  {
    const double p_star = ratio * a.sigma_x / (1 - ratio * unit.sigma_x);
    const State c = static_state(shortening, p_star);
    double held = 0;
    const State e = explicit_state(ratio, 0, &held);
    std::printf("R = %.1f: explicit against state C: pressure %.2e, sigma_x %.2e, y+ face %.2e\n",
                ratio, e.pressure / p_star - 1, e.sigma_x / c.sigma_x - 1,
                e.y_face_u.y() / c.y_face_u.y() - 1);
    EXPECT_NEAR(held, ratio, 1e-3 * ratio);
    EXPECT_NEAR(e.pressure / e.sigma_x, ratio, 2e-4 * ratio);
    EXPECT_NEAR(e.pressure / p_star, 1.0, 2e-4);
    EXPECT_NEAR(e.sigma_x / c.sigma_x, 1.0, 2e-4);
    EXPECT_NEAR(e.y_face_u.y() / c.y_face_u.y(), 1.0, 2e-4);
    const double apparent = c.sigma_x / c.strain_x;
    const double closed_form = e_x / (1 - nu_xy * ratio);
    std::printf("R = %.1f: p* = %.6g Pa, explicit %.6g Pa (ratio held %.6f); E_app %.6g, "
                "E_x / (1 - nu R) %.6g (E_x %.6g, nu_xy %.4f): %.3e\n",
                ratio, p_star, e.pressure, held, apparent, closed_form, e_x, nu_xy,
                apparent / closed_form - 1);
    EXPECT_NEAR(apparent / closed_form, 1.0, 0.02);
  }
}

// The crack-orientation histogram (crack_orientation.h): normals at known angles land in their
// bins, and an isotropic population fills the bins as the sphere's area does (within four
// standard deviations of the binomial count).
TEST(CrackOrientation, KnownAnglesAndIsotropicBaseline)
{
  constexpr double degree = std::numbers::pi / 180;
  std::vector<CrackEvent> cracks;
  for (double theta : {5.0, 15.0, 89.0, 61.0, 30.5})
  {
    CrackEvent c;
    // load axis y; the normal's other part along z
    c.axis = Vec3(0, std::cos(theta * degree), -std::sin(theta * degree));
    cracks.push_back(c);
  }
  const CrackOrientation h = crack_orientation(cracks, 1, 9);
  EXPECT_EQ(h.counts, (std::vector<long>{1, 1, 0, 1, 0, 0, 1, 0, 1}));
  EXPECT_NEAR(h.mean_angle, (5.0 + 15.0 + 89.0 + 61.0 + 30.5) / 5, 1e-9);
  EXPECT_DOUBLE_EQ(h.along_load_fraction, 0.4);
  double total = 0;
  for (double f : h.isotropic_fraction)
    total += f;
  EXPECT_NEAR(total, 1.0, 1e-14);

  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  cracks.assign(20000, CrackEvent{});
  for (auto& c : cracks)
    c.axis = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
  const CrackOrientation iso = crack_orientation(cracks, 0, 9);
  for (std::size_t k = 0; k < 9; ++k)
  {
    const double p = iso.isotropic_fraction[k], n = double(cracks.size());
    EXPECT_NEAR(double(iso.counts[k]), p * n, 4 * std::sqrt(n * p * (1 - p))) << "bin " << k;
  }
  EXPECT_NEAR(iso.mean_angle, 57.2958, 0.5); // the mean of theta over the sphere is 1 radian
}

// Bad pressures: one line naming the load and the key.
TEST(Confinement, RefusesBadPressures)
{
  auto message = [](auto edit)
  {
    CaseConfig c = block_case(shortening, 0, 0.3, false);
    edit(c);
    try
    {
      build_model(c);
    }
    catch (const InputError& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message([](CaseConfig&) {}), "");
  EXPECT_EQ(message([](CaseConfig& c) { c.loads[1].load.area = 0; }).rfind("Load confine/area:", 0),
            0u);
  EXPECT_EQ(message([](CaseConfig& c) { c.loads[1].load.value = Vec3::Zero(); })
                .rfind("Load confine/value:", 0),
            0u);
  EXPECT_EQ(message([](CaseConfig& c) { c.loads[1].ratio_load.clear(); })
                .rfind("Load confine/ratio load:", 0),
            0u);
  EXPECT_EQ(message([](CaseConfig& c) { c.loads[1].ratio_load = "nothing"; })
                .rfind("Load confine/ratio load: no load named 'nothing'", 0),
            0u);
  EXPECT_EQ(message([](CaseConfig& c) { c.loads[0].load.area = 0; }).rfind("Load drive/area:", 0),
            0u);
  EXPECT_EQ(message([](CaseConfig& c) { c.loads[0].load.kind = LoadKind::force; })
                .rfind("Load confine/ratio load: 'drive' must prescribe", 0),
            0u);
  // the static solver takes p_0 only
  CaseConfig c = block_case(shortening, 0, 0.3, true);
  Model m = build_model(c);
  try
  {
    solve_static(m);
    ADD_FAILURE() << "a ratio in a static run was taken";
  }
  catch (const InputError& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind("Load confine/ratio:", 0), 0u) << e.what();
  }
}
