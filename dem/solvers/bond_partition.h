#pragma once
// Bonds grouped for threads that never write the same particle (no atomics).
//
// The particles are split into T contiguous index chunks; with particles in spatial order
// (dem/model/renumbering.h: a space-filling curve, or a lattice's generation order) each chunk is
// a compact region and each thread writes its own contiguous block of particle memory, sharing at
// most the cache line at a chunk's end. A bond whose particles lie in one chunk belongs to that
// chunk (phase 0, the chunks in parallel); a bond between chunks s and s+1 is cut (phase 1: s
// even, phase 2: s odd, each in parallel: no two ranges of a phase share a chunk); any other
// bond is left to phase 3 (serial). Within a bucket bonds keep their order.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace dembridge::dem
{
struct BondPartition
{
  /// New bond k is old bond order[k].
  std::vector<std::size_t> order;
  /// Bond ranges [first, last) in the new order, per phase (4 phases, see above).
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> phases;
};

/// Partition of the bonds (a[k], b[k]) among @p threads over @p n_particles particles.
BondPartition partition_bonds_by_index(const std::vector<std::int32_t>& a,
                                       const std::vector<std::int32_t>& b, std::size_t n_particles,
                                       int threads);
} // namespace dembridge::dem
