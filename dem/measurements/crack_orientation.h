#pragma once
// Orientation of the crack planes against the load axis: a broken bond's crack plane is normal
// to its axis at failure (CrackEvent::axis), so its normal makes the angle
//   theta = arccos |n . e_load|,   0 <= theta <= 90 degrees,
// with the load axis. Axial splitting (cracks along the load) puts the normals near 90 degrees,
// cracks across the load near 0, and Coulombic faults at 28-30 degrees from the shortening
// direction (Schulson 2002) near 60. The histogram has equal bins in theta; the share of
// normals an isotropic crack population puts in [theta_lo, theta_hi] is
// cos theta_lo - cos theta_hi (the sphere's area), given beside it as the baseline.
#include "dem/bonds/bond_damage.h"
#include <vector>

namespace dembridge::dem
{
struct CrackOrientation
{
  int axis = 0;
  std::vector<double> edges;              ///< bins + 1 edges of theta, degrees
  std::vector<long> counts;               ///< cracks per bin
  std::vector<double> fraction;           ///< counts / cracks (0 without cracks)
  std::vector<double> isotropic_fraction; ///< cos theta_lo - cos theta_hi
  double mean_angle = 0;                  ///< mean theta, degrees (0 without cracks)
  /// share of the cracks whose planes lie within 30 degrees of the load axis (theta >= 60)
  double along_load_fraction = 0;
};

/// Histogram of theta over @p cracks in @p bins equal bins; throws std::invalid_argument for
/// an axis outside 0..2 or no bins.
CrackOrientation crack_orientation(const std::vector<CrackEvent>& cracks, int axis, int bins);
} // namespace dembridge::dem
