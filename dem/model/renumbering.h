#pragma once
// Spatial order of the particles and bonds (issue 12): at setup the particles are renumbered
// along a space-filling curve (Morton / Z-order of their reference centres on a 2^21 grid over
// the bounding cube), so that particles near in space are near in memory. Bonds keep their
// ends (a stays a, b stays b: the same bond, the same constants, strengths and state) with the
// particle indices mapped, and are sorted by their first particle in the new numbering (then
// the second), so that consecutive bonds share particles. Then
//  - the bond loop reuses each particle's cache lines across its bonds;
//  - contiguous particle index chunks are compact regions, which the thread partition
//    (dem/solvers/bond_partition.h) hands to one thread each, on random packings as on lattices.
// Renumbering permutes already-built stores, so the physics is identical: only the order of
// floating-point sums changes. The user's numbering travels with the particles
// (ParticleStore::id) for outputs.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/model/groups.h"
#include <vector>

namespace dembridge::dem
{
/// Morton order of the points: order[new] = old (stable: equal keys keep their order).
std::vector<std::size_t> morton_order(const std::vector<Vec3>& points);

/// Puts the particles in the order @p order (new i = old order[i]), every per-particle array
/// alike; maps the bonds' particle indices and the groups' members (sorted) along and sorts the
/// bonds by (first, second) particle of each bond in the new numbering, stably.
void renumber_particles(ParticleStore& p, BondStore& b, std::vector<Group>* groups,
                        const std::vector<std::size_t>& order);

/// renumber_particles along morton_order of the reference positions.
void renumber_spatially(ParticleStore& p, BondStore& b, std::vector<Group>* groups = nullptr);
} // namespace dembridge::dem
