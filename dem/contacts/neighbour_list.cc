#include "dem/contacts/neighbour_list.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace dembridge::dem
{
double NeighbourList::max_displacement(const std::vector<Vec3>& x) const
{
  if (x_built_.size() != x.size())
    return std::numeric_limits<double>::infinity();
  double largest = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    largest = std::max(largest, (x[i] - x_built_[i]).squaredNorm());
  return std::sqrt(largest);
}

bool NeighbourList::needs_rebuild(const std::vector<Vec3>& x) const
{
  if (builds_ == 0 || x_built_.size() != x.size())
    return true;
  const double limit = 0.25 * skin_ * skin_; // (s/2)^2
  for (std::size_t i = 0; i < x.size(); ++i)
    if ((x[i] - x_built_[i]).squaredNorm() > limit)
      return true;
  return false;
}

void NeighbourList::invalidate()
{
  first_.clear(), second_.clear(), previous_.clear(), x_built_.clear();
}

void NeighbourList::build(const std::vector<Vec3>& x, const std::vector<double>& r,
                          std::size_t owned)
{
  const std::size_t n = x.size();
  std::swap(first_, old_first_);
  std::swap(second_, old_second_);
  first_.clear();
  second_.clear();
  x_built_ = x;
  ++builds_;
  if (n == 0)
  {
    previous_.clear();
    return;
  }

  // Cell list over the particles' current bounding box. Cells at least 2 R_max + s wide; if
  // particles have flown far apart the cells grow so that there are never many more cells than
  // particles (slower, still exact).
  Vec3 lo = x[0], hi = x[0];
  double r_max = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    lo = lo.cwiseMin(x[i]);
    hi = hi.cwiseMax(x[i]);
    r_max = std::max(r_max, r[i]);
  }
  double h = std::max(2.0 * r_max + skin_, 1e-300);
  std::array<long, 3> nc{};
  for (;;)
  {
    for (int d = 0; d < 3; ++d)
      nc[d] = long(std::floor((hi[d] - lo[d]) / h)) + 1;
    if (double(nc[0]) * double(nc[1]) * double(nc[2]) <= 2.0 * double(n) + 27.0)
      break;
    h *= 1.25;
  }
  const long ncell = nc[0] * nc[1] * nc[2];
  auto coord = [&](const Vec3& p, int d)
  { return std::clamp<long>(long((p[d] - lo[d]) / h), 0, nc[d] - 1); };
  cell_of_.resize(n);
  cell_start_.assign(std::size_t(ncell) + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    cell_of_[i] = std::int32_t((coord(x[i], 2) * nc[1] + coord(x[i], 1)) * nc[0] + coord(x[i], 0));
    ++cell_start_[std::size_t(cell_of_[i]) + 1];
  }
  for (long c = 0; c < ncell; ++c)
    cell_start_[std::size_t(c) + 1] += cell_start_[std::size_t(c)];
  cell_members_.resize(n);
  // fill in increasing particle order: each cell's members come sorted
  fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    cell_members_[std::size_t(fill_[std::size_t(cell_of_[i])]++)] = std::int32_t(i);

  // Pairs in (i, j) order: particle i scans its 27 cells for j > i, then sorts its few j.
  for (std::size_t i = 0; i < std::min(n, owned); ++i)
  {
    const std::size_t begin = second_.size();
    const long c = cell_of_[i];
    const long cx = c % nc[0], cy = (c / nc[0]) % nc[1], cz = c / (nc[0] * nc[1]);
    for (long z = std::max(0L, cz - 1); z <= std::min(nc[2] - 1, cz + 1); ++z)
      for (long y = std::max(0L, cy - 1); y <= std::min(nc[1] - 1, cy + 1); ++y)
        for (long xc = std::max(0L, cx - 1); xc <= std::min(nc[0] - 1, cx + 1); ++xc)
        {
          const long cell = (z * nc[1] + y) * nc[0] + xc;
          for (std::int32_t k = cell_start_[std::size_t(cell)];
               k < cell_start_[std::size_t(cell) + 1]; ++k)
          {
            const std::int32_t j = cell_members_[std::size_t(k)];
            if (std::size_t(j) <= i)
              continue;
            const double reach = r[i] + r[std::size_t(j)] + skin_;
            if ((x[std::size_t(j)] - x[i]).squaredNorm() < reach * reach)
              second_.push_back(j);
          }
        }
    std::sort(second_.begin() + long(begin), second_.end());
    first_.resize(second_.size(), std::int32_t(i));
  }

  // Merge with the old list (both sorted by (i, j)): where each pair was before.
  auto key = [](std::int32_t i, std::int32_t j)
  { return (std::uint64_t(std::uint32_t(i)) << 32) | std::uint32_t(j); };
  previous_.resize(first_.size());
  std::size_t o = 0;
  const std::size_t n_old = old_first_.size();
  for (std::size_t k = 0; k < first_.size(); ++k)
  {
    const std::uint64_t kk = key(first_[k], second_[k]);
    while (o < n_old && key(old_first_[o], old_second_[o]) < kk)
      ++o;
    previous_[k] =
        o < n_old && key(old_first_[o], old_second_[o]) == kk ? std::int32_t(o) : std::int32_t(-1);
  }
}
} // namespace dembridge::dem
