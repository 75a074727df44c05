#include "dem/model/renumbering.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <tuple>

namespace dembridge::dem
{
namespace
{
template <class T> void permute(std::vector<T>& v, const std::vector<std::size_t>& order)
{
  if (v.empty())
    return;
  std::vector<T> copy(v.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    copy[k] = v[order[k]];
  v.swap(copy);
}
} // namespace

std::vector<std::size_t> row_order(const std::vector<Vec3>& points, double spacing)
{
  const std::size_t n = points.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  if (n < 2 || !(spacing > 0))
    return order;
  Vec3 lo = points[0], hi = points[0];
  for (const auto& x : points)
    lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  // axes by extent: the longest is the slowest (layers across it are smallest), the shortest
  // the fastest (rows along it)
  std::array<int, 3> axis{0, 1, 2};
  const Vec3 size = hi - lo;
  std::stable_sort(axis.begin(), axis.end(), [&](int p, int q) { return size[p] > size[q]; });
  // layer, row, position along the row; then the exact coordinates, so that spheres sharing a
  // wall (equal along-row coordinates) are ordered by where they are, not by how they came in
  using Key = std::tuple<long, long, double, double, double>;
  std::vector<Key> key(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3 d = points[i] - lo;
    key[i] = {long(std::floor(d[axis[0]] / spacing)), long(std::floor(d[axis[1]] / spacing)),
              d[axis[2]], d[axis[1]], d[axis[0]]};
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return key[x] < key[y]; });
  return order;
}

void renumber_particles(ParticleStore& p, BondStore& b, std::vector<Group>* groups,
                        const std::vector<std::size_t>& order)
{
  const std::size_t n = p.size();
  permute(p.position, order), permute(p.reference_position, order);
  permute(p.velocity, order), permute(p.angular_velocity, order);
  permute(p.orientation, order), permute(p.force, order), permute(p.torque, order);
  permute(p.radius, order), permute(p.mass, order), permute(p.inertia, order);
  permute(p.dof_mask, order), permute(p.group_mask, order);
  permute(p.coordination, order), permute(p.id, order), permute(p.grain, order);
  std::vector<std::int32_t> new_index(n);
  for (std::size_t i = 0; i < n; ++i)
    new_index[order[i]] = std::int32_t(i);
  for (std::size_t k = 0; k < b.size(); ++k)
    b.a[k] = new_index[std::size_t(b.a[k])], b.b[k] = new_index[std::size_t(b.b[k])];
  // consecutive bonds share their first particle; a bond keeps its ends (a, b)
  std::vector<std::size_t> bond_order(b.size());
  std::iota(bond_order.begin(), bond_order.end(), std::size_t(0));
  auto key = [&](std::size_t k)
  { return std::pair(std::min(b.a[k], b.b[k]), std::max(b.a[k], b.b[k])); };
  std::stable_sort(bond_order.begin(), bond_order.end(),
                   [&](std::size_t x, std::size_t y) { return key(x) < key(y); });
  b.reorder(bond_order);
  if (groups)
    for (auto& g : *groups)
    {
      for (int& i : g.members)
        i = new_index[std::size_t(i)];
      std::sort(g.members.begin(), g.members.end());
    }
}

void renumber_spatially(ParticleStore& p, BondStore& b, std::vector<Group>* groups)
{
  if (p.size() < 2)
    return;
  double mean = 0;
  for (double r : p.radius)
    mean += r;
  mean /= double(p.size());
  renumber_particles(p, b, groups, row_order(p.reference_position, 2 * mean));
}
} // namespace dembridge::dem
