// A weak plane that breaks and then slides several particle radii under a normal load, its
// load passing from pair to pair as pairs across it leave reach and come within it
// (contacts/joint_contact.h, eq. 8b-10). The energy balance of the leapfrog (dem/core/energy.h)
//   kinetic + bond strain + contact stored + damping + fracture + friction = work of the loads
// holds: from the plane's break to the end its error changes by less than 1e-4 of the largest
// term (the sliding books every spring that leaves or arrives), the break itself moves it by
// less than 5e-3 of the largest term then, and at the end it is below 1e-3. The joints' friction
// over the sliding is Coulomb's work on a plane of friction coefficient mu_j,
//   W_f = mu_j N s,                                                                       (1)
// N the normal load, s the slip of the block above the plane, to 2 %.
// The specimen: a random packing (r = 1.5 mm) in a shear box, as the single-plane test's
// (test_single_plane.cc): the particles more than one radius below the plane (normal x) held,
// those more than one radius above it slid along y as a whole, free along x, the x+ face under
// sigma_n; the plane's bonds are smooth joints an eighth as strong as the rest, sliding joints
// once broken, with mu_j = tan 30 degrees; pairs across the plane that never had a bond take
// the contact law, as stiff as the plane's bonds.
#include "dem/contacts/contact_forces.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include "face_group.h"
#include "weak_plane_specimen.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>

using namespace dembridge::dem;

namespace
{
constexpr double deg = std::numbers::pi / 180;
constexpr double radius = 1.5e-3; // m

/// The shear box of the header: sigma_n on x+, the upper block slid by @p slide along y over
/// @p duration.
CaseConfig shear_box(const Vec3& box, double sigma_n, double slide, double duration)
{
  CaseConfig c = dembridge::test::strong_rock(box, radius);
  const double cut = 0.5 * box.x() + 0.31 * radius; // the plane
  dembridge::test::add_weak_plane(c, Vec3::UnitX(), cut);
  c.contacts.model = ContactModel::linear;
  c.contacts.normal_stiffness = 9.4e5; // the plane's bonds' k_n: new pairs as stiff as old
  c.contacts.restitution = 0.3;
  c.contacts.friction = 0.5;

  GroupConfig lower{"lower", {}, dof_ux | dof_uy | dof_uz, 0, Vec3::Zero()};
  lower.selection.kind = GroupSelection::Kind::box;
  lower.selection.box_min = Vec3(-1, -1, -1);
  lower.selection.box_max = Vec3(cut - radius, 1, 1);
  GroupConfig upper{"upper", {}, dof_uz, 0, Vec3::Zero()};
  upper.selection.kind = GroupSelection::Kind::box;
  upper.selection.box_min = Vec3(cut + radius, -1, -1);
  upper.selection.box_max = Vec3(1, 1, 1);
  c.groups = {lower, upper, dembridge::test::face_group("x+", 0, true, 0)};
  const double area = box.y() * box.z();
  LoadConfig shear;
  shear.group = "upper";
  shear.load.name = "shear";
  shear.load.kind = LoadKind::displacement;
  shear.load.value = Vec3(0, slide, 0);
  shear.load.area = area;
  shear.load.components = 2;
  shear.load.ramp_time = duration;
  shear.load.profile = RampProfile::smooth;
  LoadConfig normal;
  normal.group = "x+";
  normal.load.name = "normal";
  normal.load.kind = LoadKind::pressure;
  normal.load.value = Vec3(-1, 0, 0);
  normal.load.area = area;
  normal.load.pressure = sigma_n;
  normal.load.ramp_time = 0.2e-3;
  c.loads = {shear, normal};
  return c;
}
} // namespace

TEST(SlidingPlaneEnergy, BalanceClosesAndFrictionIsCoulombsWork)
{
  const Vec3 box(0.018, 0.030, 0.012);
  const double sigma_n = 1e6, slide = 5 * radius, duration = 6e-3;
  const double mu_j = std::tan(30 * deg), normal_load = sigma_n * box.y() * box.z();
  Model m = build_model(shear_box(box, sigma_n, slide, duration));
  ExplicitSolver s(m.particles, m.bonds, m.groups, m.constraints, m.loads,
                   {m.time_step, 0.7, 1, 0.0});
  const ContactForces* contacts = nullptr;
  for (auto& contribution : m.contributions)
  {
    s.add_contribution(contribution.get());
    if (auto* c = dynamic_cast<const ContactForces*>(contribution.get()))
      contacts = c;
  }
  ASSERT_NE(contacts, nullptr);
  const auto plane_bonds =
      long(m.microstructure.bonds_per_class[std::size_t(BondClass::weak_plane)]);
  ASSERT_GT(plane_bonds, 20);
  long plane_broken = 0;
  std::size_t seen = 0;
  double largest = 0, worst_before = 0, error_at_break = 0, drift = 0;
  double friction_at_break = 0, slip_at_break = 0;
  bool broken = false;
  // the balance's signed error (dem/core/energy.h: error() is its size)
  auto signed_error = [&]
  {
    const EnergyBalance& e = s.energy();
    return e.internal() - e.external - e.wall_work - e.initial;
  };
  for (long step = 0; s.time() < duration; ++step)
  {
    for (; seen < s.cracks().size(); ++seen)
      plane_broken += s.bonds().bond_class[s.cracks()[seen].bond] == BondClass::weak_plane;
    const bool breaks_now = !broken && plane_broken == plane_bonds;
    const bool record = step % 50 == 0 || breaks_now;
    if (breaks_now) // the state after the last step: the plane has just broken
    {
      broken = true;
      friction_at_break = contacts->joint_friction();
      slip_at_break = s.group_mean_displacement(1).y();
    }
    s.step(record);
    if (!record)
      continue;
    largest = std::max(largest, s.energy().largest());
    if (breaks_now)
      error_at_break = signed_error();
    if (!broken)
      worst_before = std::max(worst_before, s.energy().error() / largest);
    else
      drift = std::max(drift, std::abs(signed_error() - error_at_break) / largest);
  }
  ASSERT_TRUE(broken);
  const double slip = s.group_mean_displacement(1).y() - slip_at_break;
  const double friction = contacts->joint_friction() - friction_at_break;
  const double coulomb = mu_j * normal_load * slip; // eq. (1)
  std::printf("plane broken at slip %.3f mm; then slid %.3f mm (%.1f radii): joints' friction "
              "%.4f J, mu_j N s %.4f J (ratio %.4f); balance error up to the break %.2e, at it "
              "%.2e J, its drift while sliding %.2e, at the end %.2e (of %.3f J)\n",
              slip_at_break * 1e3, slip * 1e3, slip / radius, friction, coulomb, friction / coulomb,
              worst_before, error_at_break, drift, s.energy().relative_error(), largest);
  EXPECT_GT(slip, 3 * radius); // pairs across the plane renewed several times
  EXPECT_LT(worst_before, 5e-3);
  EXPECT_LT(drift, 1e-4);
  EXPECT_LT(s.energy().relative_error(), 1e-3);
  EXPECT_NEAR(friction / coulomb, 1.0, 0.02);
}
