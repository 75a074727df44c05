#pragma once
// A group of the particles on one face of the specimen, as the DEM tests hold and load it.
#include "dem/model/case_config.h"
#include <cstdint>
#include <string>

namespace dembridge::test
{
/// The particles on the lower or upper face across @p axis (0 x, 1 y, 2 z), with the DOFs in
/// @p fixed (DofBit mask) held.
inline dem::GroupConfig face_group(const std::string& name, int axis, bool upper,
                                   std::uint8_t fixed)
{
  dem::GroupConfig g{name, {}, fixed, 0, dem::Vec3::Zero()};
  g.selection.kind = dem::GroupSelection::Kind::face;
  g.selection.face_axis = axis;
  g.selection.face_upper = upper;
  return g;
}
} // namespace dembridge::test
