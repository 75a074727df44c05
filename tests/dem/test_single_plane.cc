// Jaeger's single plane of weakness (Jaeger 1960; Jaeger, Cook & Zimmerman, Fundamentals of
// Rock Mechanics, 4th ed., section 10.2): a specimen with one plane of cohesion c_w and friction
// coefficient mu_w = tan phi_w whose normal makes the angle beta with sigma_1 slips on it when
//   sigma_1 - sigma_3 = 2 (c_w + mu_w sigma_3) / ((1 - mu_w cot beta) sin 2 beta)           (1)
// is below the intact strength; the least strength is at beta = 45 + phi_w / 2 degrees, and the
// plane cannot slip for beta <= phi_w (the denominator's sign).
// On a random packing (r = 1.5 mm) whose weak-plane bonds are smooth joints
// (bonds/smooth_joint.h) an eighth as strong as the rest (Mohr-Coulomb, 30 degrees) and a tenth
// as stiff (a joint more compliant than the rock around it: its own compliance then sets how
// its bonds share the load, not the packing's force chains next to it), and whose
// pairs across the plane slide on it once their bonds break (contacts/joint_contact.h, with the
// bonds' own friction, mu_j = tan 30: the plane loses its cohesion when it breaks and keeps its
// friction, the plane Jaeger's theory describes):
//  - c_w and mu_w from two direct shears of a one-plane specimen in a shear box (the half below
//    the plane held and the half above slid as a whole, beyond one radius of the plane, free to
//    dilate, under sigma_n);
//  - the plane's normal at beta from the load, unconfined and under sigma_3 = 1 MPa on both
//    side faces, the ends on rollers; beta up to 70 degrees, where the plane still leaves the
//    box through its sides (at 75 it would run into the loaded ends).
// The strength in both tests is the specimen's peak: a broken joint slides on the plane with
// its friction and never interlocks, so nothing carries the load past the plane's failure.
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include "face_group.h"
#include "weak_plane_specimen.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

using namespace dembridge::dem;

namespace
{
constexpr double deg = std::numbers::pi / 180;
constexpr double radius = 1.5e-3; // m

using dembridge::test::face_group;

/// A random packing of @p box with strong bonds, brittle, Mohr-Coulomb, and one weak plane of
/// normal @p normal through the box's centre (none for a zero normal), its bonds smooth joints
/// an eighth as strong and a tenth as stiff, sliding joints once broken; linear frictional
/// contacts elsewhere.
CaseConfig specimen(const Vec3& box, const Vec3& normal)
{
  CaseConfig c = dembridge::test::strong_rock(box, radius);
  if (normal.squaredNorm() > 0)
  {
    const Vec3 n = normal.normalized();
    dembridge::test::add_weak_plane(c, n, n.dot(0.5 * box) + 0.31 * radius);
  }
  c.contacts.model = ContactModel::linear;
  c.contacts.normal_stiffness = 2e7;
  c.contacts.restitution = 0.3;
  c.contacts.friction = 0.5;
  return c;
}

LoadConfig load(const std::string& group, const std::string& name, LoadKind kind, Vec3 value,
                double area)
{
  LoadConfig l;
  l.group = group;
  l.load.name = name;
  l.load.kind = kind;
  l.load.value = value;
  l.load.area = area;
  return l;
}

/// Runs @p c for @p duration and returns the largest reference stress of load 0. It stops once
/// a bond has broken and the stress has fallen to half its peak (a confined specimen's axial
/// stress first jumps with the confining ramp and falls back, before anything breaks), or once
/// every bond of the plane has broken and the stress lies a tenth below its peak (the plane
/// slides on its friction: the peak is behind).
double peak_stress(const CaseConfig& c, double duration)
{
  Model m = build_model(c);
  ExplicitSolver s(m.particles, m.bonds, m.groups, m.constraints, m.loads,
                   {m.time_step, 0.7, 1, 0.0});
  for (auto& contribution : m.contributions)
    s.add_contribution(contribution.get());
  const auto plane_bonds =
      long(m.microstructure.bonds_per_class[std::size_t(BondClass::weak_plane)]);
  double peak = 0;
  std::size_t seen = 0;
  long plane_broken = 0;
  while (s.time() < duration)
  {
    s.step();
    const double sigma = s.reference_stress(0);
    for (; plane_bonds > 0 && seen < s.cracks().size(); ++seen)
      plane_broken += s.bonds().bond_class[s.cracks()[seen].bond] == BondClass::weak_plane;
    peak = std::max(peak, sigma);
    if (sigma < 0.5 * peak && s.time() > 0.1 * duration && !s.cracks().empty()) // failed
      break;
    if (plane_bonds > 0 && plane_broken == plane_bonds && sigma < 0.9 * peak)
      break;
  }
  return peak;
}

/// Direct shear of a one-plane specimen (plane x = const), as in a shear box: the particles
/// more than one radius below the plane held, those more than one radius above it slid along y
/// as a whole (free along x), the x+ face under the normal stress @p sigma_n; the layer at the
/// plane deforms, as the material around the plane does in compression. The peak shear stress.
double direct_shear(double sigma_n)
{
  const Vec3 box(0.024, 0.036, 0.012);
  CaseConfig c = specimen(box, Vec3::UnitX());
  const double cut = 0.5 * box.x() + 0.31 * radius; // the plane
  GroupConfig lower{"lower", {}, dof_ux | dof_uy | dof_uz, 0, Vec3::Zero()};
  lower.selection.kind = GroupSelection::Kind::box;
  lower.selection.box_min = Vec3(-1, -1, -1);
  lower.selection.box_max = Vec3(cut - radius, 1, 1);
  GroupConfig upper{"upper", {}, dof_uz, 0, Vec3::Zero()};
  upper.selection.kind = GroupSelection::Kind::box;
  upper.selection.box_min = Vec3(cut + radius, -1, -1);
  upper.selection.box_max = Vec3(1, 1, 1);
  c.groups = {lower, upper, face_group("x+", 0, true, 0)};
  const double area = box.y() * box.z(), duration = 3e-3;
  LoadConfig shear = load("upper", "shear", LoadKind::displacement, Vec3(0, 1e-4, 0), area);
  shear.load.components = 2;
  shear.load.ramp_time = duration;
  shear.load.profile = RampProfile::smooth; // no jump in velocity at the start
  LoadConfig normal = load("x+", "normal", LoadKind::pressure, Vec3(-1, 0, 0), area);
  normal.load.pressure = sigma_n;
  normal.load.ramp_time = 0.2e-3;
  c.loads = {shear, normal};
  return peak_stress(c, duration);
}

/// Compression along x of the box with the plane's normal at @p beta degrees from x in the
/// x-y plane (no plane: beta < 0), under the lateral stress @p sigma_3 on both y faces: the
/// peak axial stress.
double compression(double beta, double sigma_3)
{
  const Vec3 box(0.072, 0.024, 0.012);
  CaseConfig c =
      specimen(box, beta < 0 ? Vec3::Zero() : Vec3(std::cos(beta * deg), std::sin(beta * deg), 0));
  GroupConfig corner{"corner", {}, dof_uy | dof_uz, 0, Vec3::Zero()};
  corner.selection.kind = GroupSelection::Kind::nearest;
  corner.selection.point = Vec3::Zero();
  c.groups = {face_group("x-", 0, false, dof_ux), face_group("x+", 0, true, 0),
              face_group("y-", 1, false, 0), face_group("y+", 1, true, 0), corner};
  const double duration = 8e-3;
  LoadConfig drive =
      load("x+", "drive", LoadKind::displacement, Vec3(-6e-4, 0, 0), box.y() * box.z());
  drive.load.components = 1;
  drive.load.ramp_time = duration;
  drive.load.profile = RampProfile::smooth;
  c.loads = {drive};
  if (sigma_3 > 0)
    for (int side : {-1, 1})
    {
      LoadConfig confine = load(side < 0 ? "y-" : "y+", side < 0 ? "confine-" : "confine+",
                                LoadKind::pressure, Vec3(0, -side, 0), box.x() * box.z());
      confine.load.pressure = sigma_3;
      confine.load.ramp_time = 0.2e-3;
      c.loads.push_back(confine);
    }
  return peak_stress(c, duration);
}
} // namespace

TEST(SinglePlane, JaegerStrengthAgainstTheAngle)
{
  // the plane's c_w and mu_w from two direct shears
  const double s1 = 0.5e6, s2 = 2e6;
  const double t1 = direct_shear(s1), t2 = direct_shear(s2);
  const double mu_w = (t2 - t1) / (s2 - s1), c_w = t1 - mu_w * s1;
  const double phi_w = std::atan(mu_w) / deg;
  std::printf("direct shear: tau %.3f MPa at sigma_n %.2f MPa, %.3f MPa at %.2f MPa: c_w %.3f "
              "MPa, phi_w %.1f degrees\n",
              t1 / 1e6, s1 / 1e6, t2 / 1e6, s2 / 1e6, c_w / 1e6, phi_w);
  const double intact = compression(-1, 0);
  std::printf("intact: peak %.3f MPa\n", intact / 1e6);
  auto jaeger = [&](double beta, double sigma_3) // eq. (1)
  {
    const double b = beta * deg;
    return sigma_3 + 2 * (c_w + mu_w * sigma_3) / ((1 - mu_w / std::tan(b)) * std::sin(2 * b));
  };
  // outside the window (beta <= phi_w: the plane cannot slip) the intact strength
  const double steep = compression(20, 0);
  std::printf("beta 20: peak %.3f MPa (intact %.3f)\n", steep / 1e6, intact / 1e6);
  EXPECT_LT(20, phi_w);
  EXPECT_NEAR(steep / intact, 1.0, 0.1);
  // inside it the plane's failure, eq. (1), unconfined and under sigma_3 = 1 MPa
  const std::vector<double> betas = {45, 55, 60, 65, 70};
  std::vector<double> unconfined;
  for (double sigma_3 : {0.0, 1e6})
    for (double beta : betas)
    {
      if (sigma_3 > 0 && beta != 45 && beta != 60)
        continue;
      const double plane = compression(beta, sigma_3);
      if (sigma_3 == 0)
        unconfined.push_back(plane);
      const double expected = jaeger(beta, sigma_3);
      std::printf("sigma_3 %.1f MPa, beta %.0f: the plane fails at sigma_1 %.3f MPa (eq. 1: %.3f, "
                  "ratio %.3f)\n",
                  sigma_3 / 1e6, beta, plane / 1e6, expected / 1e6, plane / expected);
      EXPECT_NEAR(plane / expected, 1.0, 0.3);
      EXPECT_LT(plane, intact); // the plane governs
    }
  // the least strength at beta = 45 + phi_w / 2: the vertex of the parabola through the lowest
  // point and its neighbours
  const std::size_t low = std::size_t(
      std::min_element(unconfined.begin() + 1, unconfined.end() - 1) - unconfined.begin());
  const double x0 = betas[low - 1], x1 = betas[low], x2 = betas[low + 1];
  const double y0 = unconfined[low - 1], y1 = unconfined[low], y2 = unconfined[low + 1];
  const double d01 = (y1 - y0) / (x1 - x0), d12 = (y2 - y1) / (x2 - x1);
  const double curvature = (d12 - d01) / (x2 - x0);
  const double vertex = 0.5 * (x0 + x1) - d01 / (2 * curvature);
  std::printf("least strength at beta %.1f degrees (45 + phi_w / 2 = %.1f)\n", vertex,
              45 + phi_w / 2);
  EXPECT_NEAR(vertex / (45 + phi_w / 2), 1.0, 0.1);
}
