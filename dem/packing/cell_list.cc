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
}

long CellList::cell_index(const Vec3& x) const
{
  long c[3];
  for (int d = 0; d < 3; ++d)
    c[d] = std::clamp<long>(long((x[d] - origin_[d]) / h_), 0, n_[d] - 1);
  return (c[2] * n_[1] + c[1]) * n_[0] + c[0];
}

void CellList::for_each_pair(const std::vector<Vec3>& x,
                             const std::function<void(int, int)>& f) const
{
  const double h2 = h_ * h_;
  for (long cz = 0; cz < n_[2]; ++cz)
    for (long cy = 0; cy < n_[1]; ++cy)
      for (long cx = 0; cx < n_[0]; ++cx)
      {
        const long c = (cz * n_[1] + cy) * n_[0] + cx;
        for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
        {
          const int i = cell_particles_[k];
          for (long dz = -1; dz <= 1; ++dz)
            for (long dy = -1; dy <= 1; ++dy)
              for (long dx = -1; dx <= 1; ++dx)
              {
                const long nx = cx + dx, ny = cy + dy, nz = cz + dz;
                if (nx < 0 || ny < 0 || nz < 0 || nx >= n_[0] || ny >= n_[1] || nz >= n_[2])
                  continue;
                const long c2 = (nz * n_[1] + ny) * n_[0] + nx;
                for (int k2 = cell_start_[c2]; k2 < cell_start_[c2 + 1]; ++k2)
                {
                  const int j = cell_particles_[k2];
                  if (j <= i)
                    continue;
                  if ((x[j] - x[i]).squaredNorm() < h2)
                    f(i, j);
                }
              }
        }
      }
}
} // namespace dembridge::dem
