#pragma once
// The fixed-region counterpart of an adaptive coupled case (docs/adaptive.md, `dembridge
// compare`): the same case with the adaptive region off and its particle region placed at the
// start as the region the adaptive run ended with, so that what growing the region costs or saves
// is seen against knowing the crack's place in advance.
//
// The region is the adaptive run's final set of grid cells (adaptive_region.h), kept as runs of
// cells along x between the grid's own cell faces (summary.json's `region_final_cells`), and
// handed to the fixed case as a gmsh volume (Coupling/particle region file, region_volume.h): one
// hexahedron per cell on the grid's faces, so neighbouring cells share their faces and only the
// union's outer faces are the region's boundary. The fixed run then keeps the packing's particles
// inside the cells (the lattice anchored at the union's lower corner, a cell face, as the
// envelope's lattice is: the same particles), lays its band along the union's faces inside the
// domain and meshes its continuum as any coupled run with a volume region (coupled_mesh.h): the
// band element size in the band, the element size beyond, not the adaptive run's envelope grid.
// Units: m.
#include "coupling/adaptive_region.h"
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

namespace dembridge::coupling
{
struct RegionCells
{
  /// Cell faces per axis over the region's bounding box (ascending).
  GridLines lines;
  /// Runs of region cells along x: {i_begin, i_end (exclusive), j, k}, indices into @ref lines.
  std::vector<std::array<int, 4>> runs;

  std::size_t n_cells() const;
  Vec3 lower() const { return {lines[0].front(), lines[1].front(), lines[2].front()}; }
  Vec3 upper() const { return {lines[0].back(), lines[1].back(), lines[2].back()}; }
  nlohmann::json to_json() const;
  /// Throws std::runtime_error naming @p where when @p j is not a region's cells.
  static RegionCells from_json(const nlohmann::json& j, const std::string& where);
};

/// The cells of @p region now.
RegionCells region_cells(const AdaptiveRegion& region);

/// Writes @p cells as a gmsh volume of hexahedra (one per cell, gmsh's ASCII format 2.2) to
/// @p file; throws std::runtime_error naming the file when it cannot be written.
void write_region_mesh(const RegionCells& cells, const std::filesystem::path& file);
} // namespace dembridge::coupling
