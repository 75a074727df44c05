#pragma once
// The FE mesh of a coupled run: a box graded along each axis so that cell faces lie on the
// planes of the handshake band (s = 0 and s = L, handshake.h), with element size h_band across the
// band and h = (h_x, h_y, h_z) elsewhere (each interval between planes gets equal cells of about
// that size; with a far element size, cells of an interval that touches a band plane grow away
// from it by a constant ratio per cell up to that size), and the cells of the particle-only region
// removed (they would carry neither mass nor stiffness: 1 - alpha = 0 there). No hanging nodes. A
// particle region given as a gmsh volume: band-sized cells over its bounding box, graded outside
// it, and the cells removed whose centre and Gauss points all lie in the particle-only region (the
// band cuts the others). Boundary names: the outer box faces x-min ... z-max (ids 0-5, as
// fem/mesh.h), and "particle-region" (id 6) for the faces left where the particle-only cells were
// cut out.
#include "coupling/handshake.h"
#include "fem/mesh.h"
#include <array>
#include <deal.II/distributed/tria.h>
#include <vector>

namespace dembridge::coupling
{
/// Volume of the removed (particle-only) cells around a vertex, an eighth of each cell: the share
/// of a node's lumped Q1 mass that the cut took away (coupled_build.cc shares the band's mass
/// by it).
struct RemovedShare
{
  dealii::Point<3> vertex;
  double volume = 0; ///< m^3, sum over the removed cells at the vertex of V_cell / 8
};

/// Per axis: values along it (cell sizes, cell faces, or pairs of planes).
using GridLines = std::array<std::vector<double>, 3>;

/// The box grid's cell sizes per axis: cells of the band element size between each pair of
/// @p planes, of the element size (growing up to the far size) elsewhere.
GridLines coupled_mesh_steps(const HandshakeGeometry& g, const GridLines& planes,
                             const Vec3& element_size, double band_element_size,
                             const Vec3& far_element_size, double growth);
/// The cell faces of a box grid with lower corner @p lo and cell sizes @p steps (ascending; the
/// same sums deal.II's subdivided_hyper_rectangle makes).
GridLines grid_lines(const Vec3& lo, const GridLines& steps);

/// A box grid's cell faces per axis given outright (ascending): an adaptive run's FE grid,
/// fine near its region and coarse elsewhere (AdaptiveRegion::fe_lines).
struct GivenGridLines
{
  GridLines lines;
};

/// @p fine_planes: pairs of planes per axis between which the cells have the band element size;
/// nullptr: the band's (Handshake::band_planes).
fem::BoundaryNames make_coupled_mesh(const Handshake& h, const Vec3& element_size,
                                     double band_element_size,
                                     dealii::parallel::distributed::Triangulation<3>& tria,
                                     std::vector<RemovedShare>* removed = nullptr,
                                     const Vec3& far_element_size = Vec3::Zero(),
                                     double growth = 1.2, const GridLines* fine_planes = nullptr);
/// The same on the grid of the lines @p grid (the sizes are not used then); nullptr: as above
/// from the band's planes.
fem::BoundaryNames make_coupled_mesh(const Handshake& h, const Vec3& element_size,
                                     double band_element_size,
                                     dealii::parallel::distributed::Triangulation<3>& tria,
                                     std::vector<RemovedShare>* removed,
                                     const Vec3& far_element_size, double growth,
                                     const GivenGridLines* grid);
} // namespace dembridge::coupling
