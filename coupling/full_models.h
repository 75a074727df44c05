#pragma once
// The two single-scale models of a coupled case, for `dembridge compare`: the same
// geometry, supports, load and packing as full DEM and as a full (elastic) FE model.
//
// Full DEM: the particle region's packing extended over the whole FE domain. For a lattice the
// origin moves by whole lattice periods (dem::lattice_axis_periods), so every particle of the
// coupled run's region sits at the same place in the full specimen (the same packing, bond for
// bond); a random packing is packed anew over the larger box (the same statistics, not the same
// spheres; said in `notes`). The FE supports become particle groups: a support line holds the
// particles whose centres lie within one diameter of it, a box face the face layer, a point its
// nearest particle, in the same components; a driven support (non-zero value) becomes a
// displacement load on its group with the coupled run's ramp. Coupling/mass damping becomes
// Damping/mass damping (the same -c m v on every particle).
//
// Full FE: the FE domain as one continuum with the particle region's own tensor (the coupled
// run's Coupling/continuum tensor), the particle notch (Particles/remove box, grown to whole
// spheres) cut out of the mesh, the same supports, and the particle load as a prescribed
// displacement of the boundary patch under the loaded group. It is elastic: its
// load-deflection line is the reference for the initial stiffness of the other two.
#include "coupling/coupled_case.h"
#include "dem/model/case_config.h"
#include "fem/parameters.h"
#include <string>
#include <vector>

namespace dembridge::coupling
{
/// An FE support as a particle group of the full-DEM model.
struct SupportGroup
{
  std::string name;              ///< support_0, support_1, ...
  std::string source;            ///< the FE entry it maps, for messages and the case file
  dem::GroupSelection selection; ///< box, face or nearest
  std::uint8_t fixed = 0;        ///< held translations (DofBit mask), zero value
  bool driven = false;           ///< non-zero FE value: a displacement load instead
  dem::Vec3 displacement = dem::Vec3::Zero(); ///< m, driven supports
  std::uint8_t driven_components = 0;         ///< bits x, y, z
};

struct FullDemLayout
{
  dem::Vec3 origin = dem::Vec3::Zero(),
            box_size = dem::Vec3::Zero(); ///< Particles/origin, box size
  std::vector<SupportGroup> supports;
  double mass_damping = 0;        ///< 1/s
  bool same_packing = false;      ///< lattice: the coupled region's particles reproduced exactly
  std::vector<std::string> notes; ///< what differs from the coupled run and why (one line each)
};

/// Builds the full-DEM case once to check it (its supports must select particles). Throws
/// std::runtime_error naming the key when the case cannot be mapped (FE loads, gmsh
/// boundaries, a lattice that cannot reach the FE box).
FullDemLayout full_dem_layout(const CoupledCase& c);

/// The DEM case of the layout: c.particles over the whole domain, with the supports.
dem::CaseConfig full_dem_case(const CoupledCase& c, const FullDemLayout& layout);

/// The particle load a full FE model reproduces: a displacement load (the DEM load of type
/// displacement on a group) and the FE boundary patch under that group.
struct FeLoadPatch
{
  std::string group;                          ///< DEM group
  fem::BoundaryPatch patch;                   ///< named "load"
  dem::Vec3 displacement = dem::Vec3::Zero(); ///< m, end value
  std::uint8_t components = 0;                ///< prescribed components
  dem::Vec3 direction = dem::Vec3::Zero();    ///< unit, along the displacement
};

struct FullFeModel
{
  fem::Parameters parameters; ///< static elasticity, box mesh with the notch removed
  FeLoadPatch load;
  std::vector<std::string> notes;
};

/// @p cell_size: about this cell size (m); @p degree: 1 or 2. Throws std::runtime_error naming
/// the key when the case has no displacement load on a group that touches an FE box face.
FullFeModel full_fe_model(const CoupledCase& c, double cell_size, unsigned int degree);
} // namespace dembridge::coupling
