#include "dem/packing/cell_list.h"
#include <algorithm>
#include <cmath>

namespace dembridge::dem
{
CellList::CellList(const std::vector<Vec3>& x, double cell_size) : h_(cell_size)
{
  if (!(cell_size > 0))
    throw InputError("cell list: cell size must be positive");
  Vec3 lo = Vec3::Constant(0), hi = Vec3::Constant(0);
  if (!x.empty())
  {
    lo = hi = x[0];
    for (const auto& p : x)
    {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  origin_ = lo;
  // counted in double first: a far-flung particle must not overflow the conversion to long
  double cells[3], total = 1;
  for (int d = 0; d < 3; ++d)
    total *= cells[d] = std::max(1.0, std::floor((hi[d] - lo[d]) / h_) + 1);
  if (!(total <= 4.0 * double(x.size()) + 1e6))
    throw InputError(
        "cell list: the particles are spread too far apart for their size (more than " +
        std::to_string(long(4.0 * double(x.size()) + 1e6)) + " cells)");
  for (int d = 0; d < 3; ++d)
    n_[d] = long(cells[d]);
  const long ncell = n_[0] * n_[1] * n_[2];
  cell_start_.assign(ncell + 1, 0);
  for (const auto& p : x)
    ++cell_start_[cell_index(p) + 1];
  for (long c = 0; c < ncell; ++c)
    cell_start_[c + 1] += cell_start_[c];
  cell_particles_.resize(x.size());
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < x.size(); ++i)
    cell_particles_[fill[cell_index(x[i])]++] = int(i);
  sorted_.resize(x.size());
  for (std::size_t k = 0; k < x.size(); ++k)
    sorted_[k] = x[cell_particles_[k]];
}

long CellList::cell_index(const Vec3& x) const
{
  long c[3];
  for (int d = 0; d < 3; ++d)
    c[d] = std::clamp<long>(long((x[d] - origin_[d]) / h_), 0, n_[d] - 1);
  return (c[2] * n_[1] + c[1]) * n_[0] + c[0];
}
} // namespace dembridge::dem
