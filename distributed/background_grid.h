#pragma once
// The background mesh of a full-DEM run on several MPI ranks: uniform cubic cells over a box that
// holds the specimen with a margin, as a p4est forest (deal.II's
// parallel::distributed::Triangulation) without degrees of freedom. Its cells decide which rank
// owns a particle (the rank that owns the cell the particle lies in) and which particles a rank
// keeps as ghosts (those in deal.II's ghost layer: the cells that share a vertex with one of its
// own). So that a rank sees both ends of every bond it holds, the cells are at least the bond
// cut-off wide: two particles closer than a cell width lie in one cell or in two that touch.
#include "dem/core/types.h"
#include "dem/model/model.h"
#include <array>
#include <cstddef>
#include <deal.II/distributed/tria.h>

namespace dembridge::distributed
{
struct BackgroundGrid
{
  dem::Vec3 origin = dem::Vec3::Zero(); ///< lower corner, m
  double cell_width = 0;                ///< m
  std::array<unsigned, 3> coarse{};     ///< coarse cells (p4est trees) per direction
  unsigned levels = 0;                  ///< global refinements of every coarse cell

  /// Cells per direction: coarse * 2^levels.
  std::array<unsigned, 3> cells() const;
  std::size_t n_cells() const;
  dem::Vec3 upper() const;
  /// Index of the cell that holds x (x fastest, then y, then z), -1 outside the grid.
  long cell_of(const dem::Vec3& x) const;
};

/// The grid over [lower, upper] with cubic cells at least @p min_cell_width wide: the coarse cells
/// as few as keep the cells cubic, each refined `levels` times; the box grows to whole cells about
/// its centre.
BackgroundGrid make_background_grid(const dem::Vec3& lower, const dem::Vec3& upper,
                                    double min_cell_width);

/// The grid for a model: cells at least 1.25 times its longest bond wide (2.5 times its largest
/// radius without bonds), so that bonds stretched by a quarter still reach into a neighbouring
/// cell at the next migration, and wide enough for about 27 particles a cell over the specimen
/// (a mesh cell costs more memory than a particle); over the spheres' extent (reference and
/// current centres) with a margin of one cell and a twentieth of the extent on every side.
BackgroundGrid background_grid_for(const dem::Model& model);

/// The p4est forest of the grid: one tree per coarse cell, refined `levels` times, partitioned
/// by cell count (a caller balancing particles repartitions with weights).
void create_background_mesh(dealii::parallel::distributed::Triangulation<3>& tria,
                            const BackgroundGrid& grid);
} // namespace dembridge::distributed
