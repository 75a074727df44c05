#pragma once
// Columnar grains: the columns of columnar (S2) sea ice as clusters of particles.
//
// Columns are the cells of a 2-D Voronoi tessellation of seed points in the plane normal to the
// column axis, extruded along the axis. A particle belongs to the column of the seed nearest its
// centre in that plane, which is what the tessellation's cells are, so no tessellator is needed.
// The seeds are the nodes of a hexagonal lattice, each moved by a seeded random offset:
//   node (i, j):  u = a (i + j/2),  v = a j sqrt(3)/2,
//   a = D sqrt(pi / (2 sqrt 3))   (hexagon area sqrt(3)/2 a^2 = pi D^2 / 4)               (1)
// so that every seed owns on average the area of a circle of the mean column diameter D (the
// equivalent-circle diameter); the offset is uniform in a disc of radius j a, j the jitter in
// [0, 1] (0: a regular honeycomb of identical hexagonal columns; larger: more irregular columns
// with a wider spread of diameters). The lattice is anchored at the origin and every seed's
// offset and c-axis are drawn from a generator keyed by the seed and the node's (i, j), so a
// column is the same wherever the specimen or particle region lies and whatever was packed.
//
// The c-axis of a column lies in the plane (columnar sea ice: Timco & Weeks 2010): at a uniform
// random angle, or aligned with a given direction up to a normal scatter of the angle (std dev
// in degrees).
// A granular top layer (the frazil or snow ice above the columns): particles whose centres lie
// within the given thickness of the specimen's upper face along the axis belong instead to
// equiaxed grains, the Voronoi cells of seeds on a simple cubic lattice of spacing
//   g = d (pi/6)^(1/3)   (cube volume g^3 = pi d^3 / 6)                                    (2)
// moved by offsets uniform in a ball of radius g/2 (d the equivalent-sphere diameter), each
// with a c-axis uniform on the sphere.
#include "dem/core/types.h"
#include <array>
#include <vector>

namespace dembridge::dem
{
struct ColumnarGrainsConfig
{
  bool enabled = false;
  int axis = 2;           ///< column axis: 0 x, 1 y, 2 z
  double diameter = 0;    ///< mean column diameter D (equivalent circle), m
  double jitter = 0.5;    ///< seed offset radius / lattice spacing, in [0, 1]
  unsigned long seed = 1; ///< seeds and c-axes
  bool c_axis_aligned = false;
  Vec3 c_axis_direction = Vec3::UnitX(); ///< aligned: projected into the plane
  double c_axis_spread = 0;              ///< aligned: std dev of the angle, degrees
  double granular_thickness = 0;         ///< top layer of granular grains, m; 0: none
  double granular_diameter = 0;          ///< their mean diameter d (equivalent sphere), m

  /// Throws InputError naming Microstructure/key when a value is out of range (specimen-free
  /// checks; check_against_specimen compares with the packing).
  void validate() const;
};

struct Grain
{
  Vec3 seed = Vec3::Zero();    ///< the seed point (its coordinate along a column axis: 0)
  Vec3 c_axis = Vec3::UnitX(); ///< unit
  bool granular = false;       ///< a grain of the granular top layer, not a column
};

struct GrainMap
{
  std::vector<Grain> grains;             ///< columns first, then the granular grains
  std::vector<std::int32_t> of_particle; ///< grain index of each particle
  std::size_t columns = 0;               ///< the first `columns` grains are columns
};

/// Grain of every particle (centres @p positions, radii @p radii): columns by eq. (1), the
/// granular top layer by eq. (2). Grain indices are compact, columns in lattice order (j, then
/// i), then granular grains likewise. Throws InputError when the column diameter is below two
/// mean particle diameters or above the specimen's width across the columns, or a granular
/// grain below two particle diameters.
GrainMap assign_grains(const std::vector<Vec3>& positions, const std::vector<double>& radii,
                       const ColumnarGrainsConfig& config);

/// Lattice spacing a of eq. (1) for the mean column diameter D.
double column_lattice_spacing(double diameter);

/// The seed of column node (i, j) of eq. (1): its (u, v) coordinates in the plane across the
/// columns, u along the axis after the column axis (cyclically), v along the next.
std::array<double, 2> column_seed(const ColumnarGrainsConfig& config, long i, long j);

/// The seed of granular node (i, j, k) of eq. (2), m.
Vec3 granular_seed(const ColumnarGrainsConfig& config, long i, long j, long k);
} // namespace dembridge::dem
