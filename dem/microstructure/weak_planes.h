#pragma once
// Weak planes: planes of a specimen whose bonds are weaker or softer than the rest (joints,
// brine layers, the boundaries between ice columns seen as planes). A bond whose axis crosses a
// plane takes the weak-plane bond class (microstructure.h).
//
// A set is a normal n (unit) with offsets o_m: the planes n.x = o_m, or with a spacing s > 0
// every plane n.x = o_m + q s, q any integer (a parallel family). The bond from x_a to x_b
// crosses the plane n.x = c when x_a and x_b lie on different sides of it, a point on the
// plane counting as above it:
//   crosses  <=>  (n.x_a < c) != (n.x_b < c)
// and, for a family, when floor((n.x - o) / s) differs between the two ends (the number of
// planes crossed is the difference).
#include "dem/core/types.h"
#include <vector>

namespace dembridge::dem
{
struct WeakPlaneSet
{
  Vec3 normal = Vec3::UnitX(); ///< unit
  std::vector<double> offsets; ///< o_m, m: the planes n.x = o_m
  double spacing = 0;          ///< s, m: > 0 repeats each plane every s along n; 0: once
};

/// The planes of @p set that the segment x_a -> x_b crosses: how many in all, and the index of
/// the first offset whose plane (or family) it crosses (-1: none).
struct PlaneCrossing
{
  long count = 0;
  int offset = -1;
};
PlaneCrossing crossed_planes(const WeakPlaneSet& set, const Vec3& xa, const Vec3& xb);

/// Checks a set against the packing's particle spacing (the mean particle diameter, m): a
/// non-zero normal, at least one offset, a family's spacing not below the particle spacing and
/// no two planes closer than it (a bond could cross both: overlapping planes). Throws
/// InputError naming `where`/key. Normalises the normal.
void check_weak_planes(WeakPlaneSet& set, double particle_spacing, const std::string& where);
} // namespace dembridge::dem
