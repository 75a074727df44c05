#pragma once
// The case files `dembridge compare` writes and runs beside the coupled case (compare.h): the
// full-DEM counterpart (coupling/full_models.h) and, for an adaptive case, the fixed-region
// counterpart (coupling/fixed_region.h). Each is the coupled case's own parameters (after
// --set) with the derived model's entries set, as a runnable .prm text.
#include "app/studies/compare.h"
#include "coupling/fixed_region.h"
#include "coupling/full_models.h"
#include <filesystem>
#include <string>

namespace dembridge::app
{
/// The full-DEM case: the particle box of the layout, the supports as groups (and driven
/// supports as loads), the mass damping and the coupled run's time step; the Coupling and FEM
/// sections left out.
std::string full_dem_text(const CompareOptions& o, const coupling::FullDemLayout& layout,
                          double time_step);

/// The fixed-region case: the adaptive region off and the adaptive run's final cells as its
/// particle region (@p region_file, a gmsh volume of them); the particle box their bounding box.
std::string coupled_fixed_text(const CompareOptions& o, const coupling::RegionCells& cells,
                               const std::filesystem::path& region_file);
} // namespace dembridge::app
