#pragma once
// The stores' part of a run's state for checkpoints (dem/core/state_archive.h): every field of
// ParticleStore and BondStore, and the crack log. The explicit solver visits these and its own
// fields (ExplicitSolver::visit_state); the layout is documented in docs/checkpoint.md.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/core/state_archive.h"
#include <vector>

namespace dembridge::dem
{
/// Every per-particle array (positions, orientations, velocities, forces, constants, masks,
/// coordination). Restoring requires the model's particle count.
void visit_particles(StateArchive& a, ParticleStore& p);

/// Every per-bond array, constants, state and damage alike, in the store's order. On restore
/// the stored bonds are matched to the model's by their particle pair, so a store whose order
/// differs (another thread count partitions the bonds differently) is permuted into this one's;
/// returns, for each bond index of the checkpoint, its index in @p b (empty when saving).
/// A checkpoint whose pairs differ from the model's is refused (InputError).
std::vector<std::size_t> visit_bonds(StateArchive& a, BondStore& b);

/// The crack log; @p bond_map (from visit_bonds) renumbers the restored events' bonds.
void visit_cracks(StateArchive& a, std::vector<CrackEvent>& cracks,
                  const std::vector<std::size_t>& bond_map);
} // namespace dembridge::dem
