#pragma once
// A rank's piece of a snapshot's bonds, for the ParaView bond files of a run on several MPI
// ranks: every bond the rank books (its end a owned, the rule the sums follow: each bond on
// exactly one rank), with its global id, between the points of its two ends (ghost ends
// included), and the broken bonds whose end b drifted out of the rank's store
// (DistributedParticles::detached_bonds), the position and id of that end asked of its owner.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include <cstdint>
#include <vector>

namespace dembridge::distributed
{
class DistributedParticles;

struct BondPiece
{
  /// The bonds' ends in the order of their user ids, with what a bond's force reads of them
  /// (position, orientation, velocity, angular velocity) and their ids; no other array is set.
  dem::ParticleStore ends;
  /// The booked bonds in the order of their ids, between indices of ends, as the rank holds
  /// them (constants, state, damage, classes).
  dem::BondStore bonds;
  std::vector<std::int64_t> ids; ///< the model's index of each bond (bond_id)
  bool classes = false;          ///< the model's bonds have classes
};

/// Collective (one all_gather of the far ends wanted and one of the answers).
BondPiece bond_piece(const DistributedParticles& particles);
} // namespace dembridge::distributed
