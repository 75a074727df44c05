#pragma once
// The columns' boundary area per volume, S_v, from a real tessellation (voro++), and the
// interface-compliance estimate of the Young's modulus across the columns that uses it.
//
// S_v. The columns are the 2-D Voronoi cells of the seeds (dem/microstructure/columnar_grains.h)
// extruded along the column axis, so S_v is the boundary length per area of the 2-D tessellation
// in the plane across the columns. voro++ (Rycroft 2009, Chaos 19, 041111) tessellates the seeds
// of every lattice node whose cell can reach the window, placed in a slab of unit thickness along
// the axis (each cell a prism); each cell is cut to the window's four sides, and
//     S_v = (1/2) sum_cells sum_{faces shared with another cell} A_face / V_window
// (each shared face is seen from both its cells). The cut cells' volumes add up to the window's
// (checked to 1e-9 of it).
//
// The estimate (Kachanov 1992, Appl. Mech. Rev. 45, 304; Sayers & Kachanov 1995, J. Geophys.
// Res. 100, 4149). A boundary of normal n opens by the displacement jump
//     [u] = B_N (n . t) n + B_T (t - (n . t) n),   t = sigma n,
// B_N and B_T its normal and shear compliance (m/Pa). Under a uniform stress the boundaries of
// area S_v per volume add the strain (1/2) S_v < [u] n + n [u] >, so a uniaxial stress sigma
// along x in the plane across the columns adds S_v sigma < B_N n_x^4 + B_T n_x^2 (1 - n_x^2) >.
// For normals uniformly distributed over the directions of the plane, < cos^4 > = 3/8 and
// < cos^2 sin^2 > = 1/8:
//     1 / E_x = 1 / E + S_v (3 B_N + B_T) / 8.
// (In 3-D, normals uniform on the sphere give < n_x^4 > = 1/5 and < n_x^2 (1 - n_x^2) > = 2/15:
// S_v (3 B_N + 2 B_T) / 15.) The uniform stress is statically admissible (it satisfies
// equilibrium and carries the traction across every boundary), so by the principle of minimum
// complementary energy the estimate bounds the compliance from above: the specimen's E_x lies on
// or above it.
#include "dem/microstructure/columnar_grains.h"

namespace dembridge::app
{
struct ColumnTessellation
{
  double boundary_area_per_volume = 0; ///< S_v (1/m)
  double window_area = 0;              ///< of the window across the columns (m^2)
  double cell_area_sum = 0;            ///< the cut cells' areas, summed (m^2; = window_area)
  long cells = 0;                      ///< cells that reach into the window
};

/// S_v of the columns of @p grains inside the box [lo, hi] (m; its extent along the column axis
/// plays no part). Throws InputError if the grains are not enabled or the box is empty across
/// the columns, std::runtime_error if the cut cells do not fill the window (a tessellation
/// failure).
ColumnTessellation column_tessellation(const dem::ColumnarGrainsConfig& grains, const dem::Vec3& lo,
                                       const dem::Vec3& hi);

/// E_x of the estimate above: 1 / (1 / E + S_v (3 B_N + B_T) / 8) (Pa; E in Pa, S_v in 1/m,
/// B_N and B_T in m/Pa).
double interface_compliance_youngs_modulus(double youngs_modulus, double boundary_area_per_volume,
                                           double normal_compliance, double shear_compliance);
} // namespace dembridge::app
