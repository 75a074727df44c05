#include "dem/solvers/bond_partition.h"
#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace dembridge::dem
{
BondPartition partition_bonds_by_index(const std::vector<std::int32_t>& a,
                                       const std::vector<std::int32_t>& b, std::size_t n_particles,
                                       int threads)
{
  const std::size_t nb = a.size();
  const int T = std::max(1, threads);
  BondPartition part;
  part.order.resize(nb);
  std::iota(part.order.begin(), part.order.end(), std::size_t(0));
  part.phases.assign(4, {});
  if (T == 1 || nb == 0 || n_particles < 2)
  {
    part.phases[3].push_back({0, nb});
    return part;
  }
  auto chunk = [&](std::int32_t i) { return int(std::size_t(i) * std::size_t(T) / n_particles); };
  // bucket: chunk s interior -> s; cut (s, s+1) -> T + s; other -> 2T
  std::vector<int> bucket(nb);
  for (std::size_t k = 0; k < nb; ++k)
  {
    const int sa = chunk(a[k]), sb = chunk(b[k]);
    bucket[k] = sa == sb ? sa : (std::abs(sa - sb) == 1 ? T + std::min(sa, sb) : 2 * T);
  }
  std::stable_sort(part.order.begin(), part.order.end(),
                   [&](std::size_t x, std::size_t y) { return bucket[x] < bucket[y]; });
  std::vector<int> sorted(nb);
  for (std::size_t k = 0; k < nb; ++k)
    sorted[k] = bucket[part.order[k]];
  auto range_of = [&](int bk)
  {
    const auto first = std::lower_bound(sorted.begin(), sorted.end(), bk) - sorted.begin();
    const auto last = std::upper_bound(sorted.begin(), sorted.end(), bk) - sorted.begin();
    return std::pair<std::size_t, std::size_t>(std::size_t(first), std::size_t(last));
  };
  for (int s = 0; s < T; ++s)
    part.phases[0].push_back(range_of(s));
  for (int s = 0; s + 1 < T; ++s)
    part.phases[1 + (s % 2)].push_back(range_of(T + s));
  part.phases[3].push_back(range_of(2 * T));
  return part;
}
} // namespace dembridge::dem
