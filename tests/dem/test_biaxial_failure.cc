// Failure mode of columnar ice under biaxial compression across the columns, as Smith &
// Schulson (1994) loaded it: sigma_1 along x, sigma_2 = R sigma_1 along y (both across the
// columns), the column axis z stress-free. Without confinement the specimen splits along the
// load through the columns' length: crack planes parallel to x and z, their normals along y.
// Confinement along y closes those cracks; the specimen fails across its free direction
// instead (out-of-plane: crack normals in the x-z plane), and its strength rises with R.
// Read from the crack normals (crack_orientation.h: their angles from y and z) of the cracks up
// to the peak of sigma_1, for R = 0 and R = 0.3 on a random packing with 20 mm columns and
// grain boundaries a third as strong (examples/columnar_biaxial.prm, 0.06 x 0.06 x 0.04 m).
#include "dem/measurements/crack_orientation.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include "face_group.h"
#include <cstdio>
#include <gtest/gtest.h>

using namespace dembridge::dem;

namespace
{
const Vec3 box(0.06, 0.06, 0.04);

using dembridge::test::face_group;

struct Outcome
{
  double peak = 0; ///< Pa, the largest sigma_1
  double near_y =
      0; ///< share of the cracks up to the peak whose normals lie within 30 degrees of y
  double near_z = 0; ///< and of z
};

/// x- and y- faces on rollers, x+ pushed along -x at a constant rate (laterally free), y+ under
/// R times the x+ face's stress; brittle bonds, linear contacts for the fragments.
Outcome biaxial(double ratio, unsigned seed)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::random;
  c.particles.radius = 2.5e-3;
  c.particles.box_size = box;
  c.particles.seed = seed;
  c.particles.density = 925;
  c.particles.scale_density_by_porosity = true;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.material.stiffness_ratio = 4.2;
  c.bonds.contact_radius_multiplier = 1.04;
  c.damage.law.mode = FailureMode::brittle;
  c.damage.tensile_strength = 1e6;
  c.damage.shear_strength = 2e6;
  c.damage.scatter = StrengthScatter::normal;
  c.damage.scatter_deviation = 0.2;
  c.damage.seed = seed;
  c.microstructure.grains.enabled = true;
  c.microstructure.grains.axis = 2;
  c.microstructure.grains.diameter = 0.02;
  c.microstructure.grains.seed = seed;
  BondClassConfig boundary = BondClassConfig::of_specimen(c.bonds.material, c.damage);
  boundary.tensile_strength = 0.33e6;
  boundary.shear_strength = 0.67e6;
  c.microstructure.grain_boundary = boundary;
  c.contacts.model = ContactModel::linear;
  c.contacts.normal_stiffness = 1.57e7;
  c.contacts.restitution = 0.3;
  c.contacts.friction = 0.5;
  c.groups = {face_group("x-", 0, false, dof_ux), face_group("x+", 0, true, 0),
              face_group("y-", 1, false, dof_uy), face_group("y+", 1, true, 0)};
  GroupConfig corner{"corner", {}, dof_uz, 0, Vec3::Zero()};
  corner.selection.kind = GroupSelection::Kind::nearest;
  corner.selection.point = Vec3::Zero();
  c.groups.push_back(corner);
  const double duration = 4e-3;
  LoadConfig drive;
  drive.group = "x+";
  drive.load.name = "drive";
  drive.load.kind = LoadKind::displacement;
  drive.load.components = 1;
  drive.load.value = Vec3(-1.2e-4, 0, 0);
  drive.load.ramp_time = duration;
  drive.load.area = box.y() * box.z();
  LoadConfig confine;
  confine.group = "y+";
  confine.load.name = "confine";
  confine.load.kind = LoadKind::pressure;
  confine.load.value = Vec3(0, -1, 0);
  confine.load.area = box.x() * box.z();
  confine.load.ratio = ratio;
  confine.ratio_load = "drive";
  c.loads = {drive, confine};
  Model m = build_model(c);
  ExplicitSolver s(m.particles, m.bonds, m.groups, m.constraints, m.loads,
                   {m.time_step, 0.7, 1, 0.0});
  for (auto& contribution : m.contributions)
    s.add_contribution(contribution.get());
  Outcome out;
  std::size_t at_peak = 0;
  while (s.time() < duration)
  {
    s.step();
    const double sigma = s.reference_stress(0);
    if (sigma > out.peak)
      out.peak = sigma, at_peak = s.cracks().size();
  }
  const std::vector<CrackEvent> before(s.cracks().begin(), s.cracks().begin() + long(at_peak));
  // within 30 degrees of an axis: the first three 10-degree bins against it
  auto near = [&](int axis)
  {
    const CrackOrientation h = crack_orientation(before, axis, 9);
    return h.fraction[0] + h.fraction[1] + h.fraction[2];
  };
  out.near_y = near(1), out.near_z = near(2);
  const CrackOrientation x = crack_orientation(before, 0, 9);
  std::printf("R = %.1f (seed %u): peak sigma_1 %.3f MPa, %zu cracks up to it (%ld in all); "
              "normals within 30 degrees of y %.3f, of z %.3f; mean angle from x %.1f degrees\n",
              ratio, seed, out.peak / 1e6, at_peak, s.n_broken_bonds(), out.near_y, out.near_z,
              x.mean_angle);
  return out;
}
} // namespace

TEST(BiaxialFailure, ConfinementTurnsSplittingOutOfPlane)
{
  // seeds 2 and 3 measured too (docs/columnar_ice.md)
  const Outcome free = biaxial(0.0, 1), confined = biaxial(0.3, 1);
  // unconfined: splitting cracks along the load through the columns (normals along y)
  EXPECT_GT(free.near_y, 1.5 * free.near_z);
  // confined: the y-normals closed, the cracks across the free column axis
  EXPECT_GT(confined.near_z, 1.5 * confined.near_y);
  // strength rises with confinement below the transition (Smith & Schulson, Fig. 5)
  EXPECT_GT(confined.peak, 1.2 * free.peak);
}
