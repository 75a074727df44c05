#pragma once
// Uniform-grid cell list for neighbour search: O(N) pair finding for bond formation and (later)
// post-failure contact detection. Cells are at least `cell_size` wide; particles are bucketed
// by centre, so pairs closer than cell_size are found among the 27 neighbouring cells.
#include "dem/core/types.h"
#include <functional>
#include <vector>

namespace dembridge::dem
{
class CellList
{
public:
  CellList(const std::vector<Vec3>& positions, double cell_size);

  /// Calls f(i, j) once for every pair i < j whose centres are closer than cell_size.
  void for_each_pair(const std::vector<Vec3>& positions,
                     const std::function<void(int, int)>& f) const;

private:
  Vec3 origin_;
  double h_;
  std::array<long, 3> n_{};
  std::vector<int> cell_start_, cell_particles_;
  long cell_index(const Vec3& x) const;
};
} // namespace dembridge::dem
