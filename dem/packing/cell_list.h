#pragma once
// Uniform-grid cell list for neighbour search: O(N) pair finding for bond formation, the random
// packing's Verlet lists and contact detection. Cells are at least `cell_size` wide; particles
// are bucketed by centre, so pairs closer than cell_size are found among the 27 neighbouring
// cells. The visiting order (cells z-y-x, particles of a cell by index, neighbour cells z-y-x,
// their particles by index) is part of the contract: bond numbering and the random packing's
// floating-point sums follow it.
#include "dem/core/types.h"
#include <algorithm>
#include <array>
#include <vector>

namespace dembridge::dem
{
class CellList
{
public:
  CellList(const std::vector<Vec3>& positions, double cell_size);

  /// Calls f(i, j) once for every pair i < j whose centres are closer than cell_size, in the
  /// order stated above. `positions` must be the ones the list was built from.
  template <class F> void for_each_pair(const std::vector<Vec3>& positions, F&& f) const;

  /// The same visit as for_each_pair, one level lower: f(i, centre_i, begin, end) for every
  /// particle i and every row of its neighbouring cells along x (slots [begin, end) of
  /// particle(), centre(): the row's cells in turn, each cell's indices ascending; empty rows
  /// skipped), without the distance and index filters. For loops that filter without branches.
  template <class F> void for_each_neighbour_cell(F&& f) const
  {
    for_each_neighbour_cell(f, 0, n_[2]);
  }
  /// The same for the cells of the z-layers [z_begin, z_end) only: consecutive ranges visit in
  /// turn what the whole visit does (threads split the layers and join their results in order).
  template <class F> void for_each_neighbour_cell(F&& f, long z_begin, long z_end) const;
  long layers() const { return n_[2]; } ///< cell layers along z
  const int* particle() const { return cell_particles_.data(); } ///< index in slot k
  const Vec3* centre() const { return sorted_.data(); }          ///< centre in slot k
  double cell_size() const { return h_; }

private:
  Vec3 origin_;
  double h_;
  std::array<long, 3> n_{};
  std::vector<int> cell_start_, cell_particles_;
  std::vector<Vec3> sorted_; ///< centres in cell order (cell_particles_), read contiguously
  long cell_index(const Vec3& x) const;
};

template <class F>
void CellList::for_each_neighbour_cell(F&& f, long z_begin, long z_end) const
{
  // why: the up to three neighbour cells of a row along x hold consecutive slots, so each row
  // is one range (nine calls instead of 27, the same particles in the same order)
  std::array<std::array<int, 2>, 9> rows;
  for (long cz = z_begin; cz < z_end; ++cz)
    for (long cy = 0; cy < n_[1]; ++cy)
      for (long cx = 0; cx < n_[0]; ++cx)
      {
        const long c = (cz * n_[1] + cy) * n_[0] + cx;
        if (cell_start_[c] == cell_start_[c + 1])
          continue;
        const long x_lo = std::max(cx - 1, 0L), x_hi = std::min(cx + 1, n_[0] - 1);
        int count = 0;
        for (long nz = std::max(cz - 1, 0L); nz <= std::min(cz + 1, n_[2] - 1); ++nz)
          for (long ny = std::max(cy - 1, 0L); ny <= std::min(cy + 1, n_[1] - 1); ++ny)
          {
            const long row = (nz * n_[1] + ny) * n_[0];
            const int begin = cell_start_[row + x_lo], end = cell_start_[row + x_hi + 1];
            if (begin < end)
              rows[count++] = {begin, end};
          }
        for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
          for (int q = 0; q < count; ++q)
            f(cell_particles_[k], sorted_[k], rows[q][0], rows[q][1]);
      }
}

template <class F> void CellList::for_each_pair(const std::vector<Vec3>& x, F&& f) const
{
  (void)x; // why: the centres are read from sorted_, the same values in cell order
  const double h2 = h_ * h_;
  for_each_neighbour_cell(
      [&](int i, const Vec3& xi, int begin, int end)
      {
        for (int k2 = begin; k2 < end; ++k2)
        {
          const int j = cell_particles_[k2];
          if (j <= i)
            continue;
          if ((sorted_[k2] - xi).squaredNorm() < h2)
            f(i, j);
        }
      });
}
} // namespace dembridge::dem
