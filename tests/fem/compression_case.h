#pragma once
// The quasi-static benchmark case (tests/fem/test_static_gamg.cc, bench/static_bench.cc): the thesis specimen
// (0.25 x 0.1 x 0.1 m, TBBM bonds, E_b = 4 GPa, nu = 0.3) as an HCP lattice or a random close
// packing, compressed by a prescribed end displacement. The supports are those of the thesis'
// compression test (examples/compression_random.prm): the x- end on rollers (ux), two corner
// particles holding the rigid-body motion across the axis, the end faces free to expand; the
// network's soft modes are held only by those two particles, which is what makes Jacobi CG slow.
#include "dem/model/model.h"

namespace dembridge::test
{
inline const dem::Vec3 compression_box(0.25, 0.1, 0.1);
inline constexpr double compression_shortening = 1e-5; // m, at x+

inline dem::CaseConfig compression_case(dem::ParticleSource::Kind kind, double radius)
{
  using namespace dembridge::dem;
  CaseConfig c;
  c.particles.kind = kind;
  c.particles.radius = radius;
  c.particles.box_size = compression_box;
  c.particles.seed = 1;
  // random packings: near-contacts within 2 % bonded, as the thesis specimens (docs/specimens.md)
  c.bonds.contact_radius_multiplier = kind == ParticleSource::Kind::random ? 1.02 : 1.0;
  c.bonds.material.model = BondModel::timoshenko;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  GroupConfig fixed{"fixed_end", {}, dof_ux, 0, Vec3::Zero()};
  fixed.selection.kind = GroupSelection::Kind::face;
  fixed.selection.face_axis = 0;
  fixed.selection.face_upper = false;
  GroupConfig loaded = fixed;
  loaded.name = "loaded_end";
  loaded.fixed = 0;
  loaded.selection.face_upper = true;
  GroupConfig corner{"corner", {}, std::uint8_t(dof_uy | dof_uz), 0, Vec3::Zero()};
  corner.selection.kind = GroupSelection::Kind::nearest;
  corner.selection.point = Vec3::Zero();
  GroupConfig corner_y{"corner_y", {}, dof_uz, 0, Vec3::Zero()};
  corner_y.selection.kind = GroupSelection::Kind::nearest;
  corner_y.selection.point = Vec3(0, compression_box.y(), 0);
  c.groups = {fixed, loaded, corner, corner_y};
  LoadConfig load;
  load.group = "loaded_end";
  load.load.name = "shortening";
  load.load.kind = LoadKind::displacement;
  load.load.value = Vec3(-compression_shortening, 0, 0);
  load.load.components = dof_ux;
  c.loads = {load};
  c.run.static_solver = true;
  return c;
}

/// Apparent modulus (F / A) / (delta / L) from the reaction on the loaded end of a solved model.
inline double compression_modulus(const dem::Model& m)
{
  double reaction = 0;
  for (int i : m.groups[m.group_index("loaded_end", "compression_modulus")].members)
    reaction -= m.particles.force[i].x();
  return reaction / (compression_box.y() * compression_box.z()) /
         (compression_shortening / compression_box.x());
}
} // namespace dembridge::test
