#pragma once
// Which particles of a bonded specimen the bonds reach, and the contact radius multiplier eta_r
// that would reach the others. Bond formation joins a pair when
//   |x_a - x_b| <= eta_r (R_a + R_b)                                   (dem/bonds/bonding.h)
// so the pair's own ratio q_ab = |x_a - x_b| / (R_a + R_b) is the smallest eta_r that bonds it:
//   closest pair          min over pairs q_ab          (eta_r below it forms no bond at all)
//   every particle bonded max over a of min over b q_ab (each particle to its nearest neighbour)
// Neighbours are searched within four times the largest radius (a ratio of 2: twice the touching
// distance); a particle with none there has no finite ratio.
#include "dem/core/particle_store.h"

namespace dembridge::dem
{
struct BondCoverage
{
  long unbonded = 0; ///< particles with no bond (coordination 0)
  /// eta_r that bonds the closest pair; 0 when no two centres lie within the search distance
  double closest_pair_multiplier = 0;
  /// eta_r that bonds every particle to its nearest neighbour; 0 when some particle has no
  /// neighbour within the search distance
  double every_particle_multiplier = 0;
};

/// Counts the particles without a bond (ParticleStore::coordination, right after formation) and
/// the two multipliers above.
BondCoverage bond_coverage(const ParticleStore& p);
} // namespace dembridge::dem
