#pragma once
// The normal and shear compliance of a plane of bonds, B_N and B_T (m/Pa), measured on a
// specimen with that one plane: the interface-compliance estimate of the Young's modulus across
// the columns needs them (column_tessellation.h; docs/columnar_ice.md).
//
// Definition: across a plane of normal n under the traction t = sigma n, the displacement jumps
// by [u] = B_N (n . t) n + B_T (t - (n . t) n): B > 0 for a plane softer than the packing.
//
// Measurement. The specimen's boundary layer (centres within 1.5 r of a face) is moved by a
// uniform strain plus the plane's own jump +-J/2 on its two sides, rotations held at 0, and the
// rest relaxes in a static solve: normal mode, uniaxial strain e n n; shear mode, pure shear
// e (n s + s n) / 2 with s the slip direction. Linear fits u = a + G x of the displacements on
// the two sides of the core (centres at least the core margin from every face, cut to whole
// lattice periods as the elasticity measurement cuts it; a mean diameter or more from the plane),
// extrapolated to the plane's point nearest the core's centre, give the jump. The same fits on
// the specimen without the plane (same packing, same strain) give the lattice's own share (its
// displacements are not affine near the held layer), which is subtracted. The traction is the
// core's mean stress (particle_stress.h, thesis eq. 54) on n. The boundary must jump with the
// plane, else it holds the plane back: the jump measured, J_out = J_0 + M J in the (n, s)
// components, is linear in the jump J put on the boundary, so three solves give the consistent
// J = (I - M)^-1 (J_0 - J_intact) and a fourth solves at it.
// On the simple cubic lattice this gives B_N = d^2 (1/k_n' - 1/k_n), B_T = d^2 (1/k_s' - 1/k_s)
// (each bond across the plane in series with its chain) to 1e-10 (tests/dem/
// test_column_compliance.cc).
#include "dem/model/case_config.h"
#include "dem/model/model.h"
#include <vector>

namespace dembridge::app
{
struct PlaneCompliance
{
  double normal = 0, shear = 0; ///< B_N, B_T (m/Pa)
  /// |jump measured - jump put on the boundary| / |jump| at the consistent jump (round-off)
  double consistency = 0;
};

/// B_N and B_T of the plane n.x = offset (unit n, slip along the unit s normal to n) of the
/// specimen @p specimen (its microstructure replaced by the one plane), the plane's bonds given
/// @p plane_bonds. @p period: the lattice's periods (lattice_axis_periods), zero for random
/// packings. Throws InputError if the plane misses the specimen's core.
PlaneCompliance plane_compliance(const dem::CaseConfig& specimen, const dem::Vec3& normal,
                                 const dem::Vec3& slip, double offset,
                                 const dem::BondClassConfig& plane_bonds, const dem::Vec3& period);

struct PlaneComplianceMean
{
  PlaneCompliance mean;              ///< over the planes below
  std::vector<double> angles;        ///< of the normals, rad, from the axis after the column axis
  std::vector<PlaneCompliance> each; ///< per angle, averaged over the offsets
};

/// B_N and B_T averaged over the directions of the planes that contain @p axis (the columns'
/// axis): normals at the midpoints of @p angles equal steps of [0, range) from the axis after
/// it (cyclically), each plane through the specimen's middle and a mean radius off it (where it
/// cuts a lattice), slip in the plane across the axis. range: pi / 6 for the HCP lattice about
/// its stacking axis z (six-fold, and even under x -> -x), else pi.
PlaneComplianceMean mean_plane_compliance(const dem::CaseConfig& specimen, int axis,
                                          const dem::BondClassConfig& plane_bonds, int angles);
} // namespace dembridge::app
