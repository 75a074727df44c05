#include "dem/model/bond_coverage.h"
#include "dem/packing/cell_list.h"
#include <algorithm>
#include <cmath>
#include <limits>

namespace dembridge::dem
{
BondCoverage bond_coverage(const ParticleStore& p)
{
  BondCoverage c;
  for (const int k : p.coordination)
    c.unbonded += k == 0;
  if (p.size() < 2)
    return c;
  const double rmax = *std::max_element(p.radius.begin(), p.radius.end());
  const CellList cells(p.position, 4.0 * rmax);
  // nearest ratio q_ab per particle (infinite: no neighbour within the search distance)
  std::vector<double> nearest(p.size(), std::numeric_limits<double>::infinity());
  cells.for_each_pair(p.position,
                      [&](int a, int b)
                      {
                        const double q =
                            (p.position[std::size_t(b)] - p.position[std::size_t(a)]).norm() /
                            (p.radius[std::size_t(a)] + p.radius[std::size_t(b)]);
                        nearest[std::size_t(a)] = std::min(nearest[std::size_t(a)], q);
                        nearest[std::size_t(b)] = std::min(nearest[std::size_t(b)], q);
                      });
  const double closest = *std::min_element(nearest.begin(), nearest.end());
  const double every = *std::max_element(nearest.begin(), nearest.end());
  c.closest_pair_multiplier = std::isfinite(closest) ? closest : 0.0;
  c.every_particle_multiplier = std::isfinite(every) ? every : 0.0;
  return c;
}
} // namespace dembridge::dem
