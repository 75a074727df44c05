// The adaptive region's non-local utilisation (adaptive_region.h), the average with the
// bell-shaped weight of Bazant & Jirasek (2002), "Nonlocal integral formulations of plasticity
// and damage: survey of progress", J. Eng. Mech. 128(11), by the cells' volumes V:
//   Ubar_c = sum_{c'} w(r) V_c' U_c' / sum_{c'} w(r) V_c',  w(r) = (1 - r^2 / R^2)^2 for r < R,
// r = |x_c - x_c'| between the grid cells' centres, over the continuum's cells (the
// particle-only region has none). The grid's lines never move, so that the cells within R of
// each cell and their distances are laid out once, per axis.
#include "coupling/adaptive_region.h"

#include <algorithm>

namespace dembridge::coupling
{
// Per axis, the grid cells whose centres may lie within R of each cell's centre, and the squared
// centre distances to them: the average's weights without searching the grid at every measure
// (its lines never move).
void AdaptiveRegion::lay_out_averaging()
{
  const double R = settings_.averaging_radius;
  for (int d = 0; d < 3; ++d)
  {
    auto& axis = averaging_axes_[d];
    const auto& l = lines_[d];
    axis.first.resize(n_[d]);
    axis.offset.resize(n_[d] + 1);
    axis.distance2.clear();
    auto cell_at = [&](double x)
    {
      const long i = long(std::upper_bound(l.begin(), l.end(), x) - l.begin()) - 1;
      return int(std::clamp(i, 0L, long(n_[d]) - 1));
    };
    for (int i = 0; i < n_[d]; ++i)
    {
      const double x = 0.5 * (l[i] + l[i + 1]);
      const int lo = cell_at(x - R), hi = cell_at(x + R);
      axis.first[i] = lo;
      axis.offset[i] = int(axis.distance2.size());
      for (int o = lo; o <= hi; ++o)
      {
        const double dx = 0.5 * (l[o] + l[o + 1]) - x;
        axis.distance2.push_back(dx * dx);
      }
    }
    axis.offset[n_[d]] = int(axis.distance2.size());
  }
}

// Ubar_c of the file comment over the continuum's cells, and its largest value.
void AdaptiveRegion::average_utilisation()
{
  const double R = settings_.averaging_radius;
  const double R2 = R * R;
  const auto& [ax, ay, az] = averaging_axes_;
  max_utilisation_ = 0;
  for (int k = 0; k < n_[2]; ++k)
    for (int j = 0; j < n_[1]; ++j)
      for (int i = 0; i < n_[0]; ++i)
      {
        const std::size_t c = cell_index(i, j, k);
        averaged_[c] = 0.f;
        if (!continuum_[c])
          continue;
        double sum = 0, weights = 0;
        for (int kk = az.offset[k]; kk < az.offset[k + 1]; ++kk)
        {
          const int ko = az.first[k] + (kk - az.offset[k]);
          for (int jj = ay.offset[j]; jj < ay.offset[j + 1]; ++jj)
          {
            const int jo = ay.first[j] + (jj - ay.offset[j]);
            if (ay.distance2[jj] + az.distance2[kk] >= R2) // r >= R whatever the x offset
              continue;
            const std::size_t row = cell_index(ax.first[i], jo, ko);
            for (int ii = ax.offset[i]; ii < ax.offset[i + 1]; ++ii)
            {
              const std::size_t o = row + std::size_t(ii - ax.offset[i]);
              if (!continuum_[o])
                continue;
              // in the order of |x_o - x_c|^2 / R^2 (the same sums as the centres' distance)
              const double r2 = (ax.distance2[ii] + ay.distance2[jj] + az.distance2[kk]) / R2;
              if (r2 >= 1)
                continue;
              const double w = (1 - r2) * (1 - r2) * cell_volume_[o];
              sum += w * utilisation_[o];
              weights += w;
            }
          }
        }
        averaged_[c] = float(weights > 0 ? sum / weights : utilisation_[c]);
        max_utilisation_ = std::max(max_utilisation_, double(averaged_[c]));
      }
}
} // namespace dembridge::coupling
