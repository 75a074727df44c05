#pragma once
// Particle groups: named sets of particle indices selected by geometry or index, used for
// supports, loads and measurements. Selections:
//   all                    every particle
//   index  i, j, ...       explicit indices; negative counts from the end (-1 = last)
//   box    min, max        centres inside the axis-aligned box [min, max] (m)
//   face   x-|x+|y-|y+|z-|z+, thickness t
//                          centres within t * r of that face of the specimen's bounding box
//                          (r = particle radius; the thesis' end zones use t = 1.5)
//   nearest point          the one particle whose reference centre is nearest the point (m):
//                          a support that holds for any packing, seed or radius
#include "dem/core/particle_store.h"
#include <string>
#include <vector>

namespace dembridge::dem
{
struct GroupSelection
{
  enum class Kind
  {
    all,
    index,
    box,
    face,
    nearest
  } kind = Kind::all;
  std::vector<long> indices;
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();
  int face_axis = 0;       ///< 0, 1, 2
  bool face_upper = false; ///< true: the + face
  double face_thickness = 1.5;
  Vec3 point = Vec3::Zero(); ///< nearest
};

struct Group
{
  std::string name;
  std::vector<int> members;
};

/// Resolves a selection; throws InputError naming `where` if it selects nothing or an index is
/// out of range.
Group select_group(const ParticleStore& p, const std::string& name, const GroupSelection& sel,
                   const std::string& where);

/// Bounding box of the spheres (radii included) in the reference configuration: the specimen
/// extent used by face groups and by the specimen measurements.
std::pair<Vec3, Vec3> reference_extent(const ParticleStore& p);

/// Mean displacement of the group's particles from the reference configuration (m).
Vec3 mean_displacement(const ParticleStore& p, const Group& g);
/// Sum of the particle forces over the group (support reactions on constrained DOFs).
Vec3 total_force(const ParticleStore& p, const Group& g);

/// Parses "x-", "z+" ... into (axis, upper).
std::pair<int, bool> parse_face(const std::string& text, const std::string& where);
} // namespace dembridge::dem
