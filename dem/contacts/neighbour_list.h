#pragma once
// Verlet neighbour list for contact detection: every pair i < j whose surfaces were closer than
// the skin s when the list was built,
//   |x_i - x_j| < R_i + R_j + s,
// found through a uniform cell list (cells of at least 2 R_max + s; each particle looks at its
// 27 cells), so a build costs O(N). Between builds no pair can come into contact unnoticed as long
// as no particle has moved more than s/2 since the build (two such particles close the gap by at
// most s): needs_rebuild() checks exactly that, O(N) per step.
// Pairs come sorted by (i, j); after a build, previous_index() maps each pair to its index in
// the list before the build (or -1), so per-contact history (tangential springs) is carried
// over by one linear merge. Builds reuse their buffers: no allocation once the list has reached
// its size.
#include "dem/core/state_archive.h"
#include "dem/core/types.h"
#include <cstdint>
#include <limits>
#include <vector>

namespace dembridge::dem
{
class NeighbourList
{
public:
  explicit NeighbourList(double skin = 0) : skin_(skin) {}

  void set_skin(double skin) { skin_ = skin; }
  double skin() const { return skin_; }

  /// True before the first build and once some particle has moved more than skin/2 since the
  /// last build.
  bool needs_rebuild(const std::vector<Vec3>& x) const;
  /// Largest displacement of a particle since the last build (m).
  double max_displacement(const std::vector<Vec3>& x) const;

  /// Finds all pairs within the skin; positions x, radii r. With @p owned < x.size() (a rank
  /// of a distributed run: ghosts after its own particles) only pairs with an end in
  /// [0, owned): a pair of two ghosts is the other ranks' to compute.
  void build(const std::vector<Vec3>& x, const std::vector<double>& r,
             std::size_t owned = std::numeric_limits<std::size_t>::max());
  /// Forgets the pairs (the particles were renumbered): the next build starts afresh, every
  /// pair new (previous_index() -1).
  void invalidate();

  std::size_t size() const { return first_.size(); }
  const std::vector<std::int32_t>& first() const { return first_; }
  const std::vector<std::int32_t>& second() const { return second_; }
  /// For each pair of the current list, its index in the list before the last build, or -1.
  const std::vector<std::int32_t>& previous_index() const { return previous_; }
  long builds() const { return builds_; }
  /// Checkpoints: the pairs and the positions at the last build (the rest is scratch of a
  /// build), so that a restored list rebuilds at the same step as the original.
  void visit_state(StateArchive& a);

private:
  double skin_;
  long builds_ = 0;
  std::vector<Vec3> x_built_;
  std::vector<std::int32_t> first_, second_, old_first_, old_second_, previous_;
  // cell list, rebuilt with the list
  std::vector<std::int32_t> cell_of_, cell_start_, cell_members_, fill_;
};
} // namespace dembridge::dem
