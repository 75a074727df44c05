#pragma once
// Spatial order of the particles and bonds. At setup the particles are renumbered by
// their reference centres into layers across the specimen's longest axis, rows within a layer
// across the middle axis (layers and rows one mean diameter thick), and along the shortest axis
// within a row: the order a lattice generator writes, for any packing. Bonds keep their ends
// (a stays a, b stays b: the same bond, constants, strengths and state) with the particle
// indices mapped, and are sorted by the lower of their two new indices (then the higher), so
// that consecutive bonds share a particle. Then
//  - a bond's other particle lies in the same row, the next row or the next layer: three
//    streams through memory that the CPU's prefetchers follow, with a working set of two
//    layers (the smallest cross-section);
//  - contiguous particle index chunks are slabs across the longest axis, which the thread
//    partition (dem/solvers/bond_partition.h) hands to one thread each, on random packings as
//    on lattices.
// Measured (bench/RESULTS.md): a Morton (Z-order) curve was slower than this order, on the
// lattice and on random packings, since its jumps defeat the prefetchers.
// Renumbering permutes already-built stores, so the physics is identical: only the order of
// floating-point sums changes. The user's numbering travels with the particles
// (ParticleStore::id) for outputs.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/model/groups.h"
#include <vector>

namespace dembridge::dem
{
/// The layer-row order above for points with the given layer and row thickness (m): order[new]
/// = old; a function of the positions alone (the input order breaks only exact coincidences).
std::vector<std::size_t> row_order(const std::vector<Vec3>& points, double spacing);

/// Puts the particles in the order @p order (new i = old order[i]), every per-particle array
/// alike; maps the bonds' particle indices and the groups' members (sorted) along and sorts the
/// bonds by (lower, higher) new particle index, stably.
void renumber_particles(ParticleStore& p, BondStore& b, std::vector<Group>* groups,
                        const std::vector<std::size_t>& order);

/// renumber_particles along row_order of the reference positions, layers one mean diameter thick.
void renumber_spatially(ParticleStore& p, BondStore& b, std::vector<Group>* groups = nullptr);
} // namespace dembridge::dem
