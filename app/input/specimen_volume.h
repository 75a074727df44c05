#pragma once
// Particles/specimen volume: a DEM specimen of any shape, cut from a generated packing. The
// packing (cubic, HCP, FCC, random) fills the bounding box of a gmsh volume mesh (which replaces
// Particles/origin and box size); a sphere is kept when it lies wholly inside the volume: its
// centre inside (coupling/region_volume.h, RegionVolume::contains) and at least the packing's
// radius (Particles/radius) from the volume's surface (SurfaceDistance), the way a core is
// drilled out of a block. Exact for the lattices and the monodisperse random packing (whose
// radii end within 0.2 % of Particles/radius); a polydisperse random packing is cut at the mean
// radius, so a sphere larger than the mean may stand out by its excess. Rows and particle
// files are refused (no packing to fill the box with).
// The cut is dembridge::dem's ParticleSource::keep: applied after the porosity is measured on
// the whole box (summary.json's porosity is the box packing's) and before bonding, so the
// groups, loads and measurements see only the specimen.
#include "dem/model/case_config.h"
#include <string>

namespace dembridge::app
{
/// Reads @p file (gmsh .msh, resolved like FEM/Mesh/file) and sets @p source to fill its
/// bounding box and keep the spheres inside it. Throws dem::InputError naming
/// Particles/specimen volume and the file when the file is missing or unreadable, when the
/// volume is thinner than two particle diameters along an axis, or (lattices) when no whole
/// sphere of the lattice fits inside. Returns the specimen's cross-section normal to each axis,
/// m^2: the volume over its length along the axis.
dem::Vec3 apply_specimen_volume(dem::ParticleSource& source, const std::string& file);
} // namespace dembridge::app
