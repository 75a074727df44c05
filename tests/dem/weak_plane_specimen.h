#pragma once
// The rock and the weak plane of the single-plane tests (test_single_plane.cc,
// test_sliding_plane_energy.cc): a random packing with strong brittle Mohr-Coulomb bonds and
// one plane whose bonds are smooth joints an eighth as strong and a tenth as stiff, sliding with
// mu_j = tan 30 degrees once broken.
#include "dem/model/case_config.h"
#include <cmath>
#include <numbers>

namespace dembridge::test
{
/// A random packing of @p box (r = @p radius, seed 3, 2,500 kg/m^3), parallel bonds (4 GPa,
/// nu 0.3, k_n/k_s 2.5, contact radius multiplier 1.04), brittle, Mohr-Coulomb with 30 degrees,
/// 8 MPa tensile strength and cohesion; no plane, no contacts.
inline dem::CaseConfig strong_rock(const dem::Vec3& box, double radius)
{
  using namespace dem;
  const double tan30 = std::tan(30 * (std::numbers::pi / 180));
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::random;
  c.particles.radius = radius;
  c.particles.box_size = box;
  c.particles.seed = 3;
  c.particles.density = 2500;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.material.stiffness_ratio = 2.5;
  c.bonds.contact_radius_multiplier = 1.04;
  c.damage.law.mode = FailureMode::brittle;
  c.damage.law.shear = ShearCriterion::mohr_coulomb;
  c.damage.friction_angle = 30;
  c.damage.law.tan_friction = tan30;
  c.damage.tensile_strength = 8e6;
  c.damage.cohesion = 8e6;
  return c;
}

/// The plane n.x = @p offset (@p normal unit) in @p c: its bonds smooth joints with 1 MPa
/// tensile strength and cohesion and a tenth of the rock's Young's modulus, sliding joints with
/// mu_j = tan 30 degrees once broken.
inline void add_weak_plane(dem::CaseConfig& c, const dem::Vec3& normal, double offset)
{
  using namespace dem;
  WeakPlaneSet plane;
  plane.normal = normal;
  plane.offsets = {offset};
  c.microstructure.weak_planes = plane;
  BondClassConfig weak = BondClassConfig::of_specimen(c.bonds.material, c.damage);
  weak.tensile_strength = 1e6;
  weak.cohesion = 1e6;
  weak.material.youngs_modulus = 0.1 * c.bonds.material.youngs_modulus;
  c.microstructure.weak_plane = weak;
  c.microstructure.smooth_joint = true;
  c.microstructure.joint_friction = std::tan(30 * (std::numbers::pi / 180));
}
} // namespace dembridge::test
