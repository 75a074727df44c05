#include "dem/model/renumbering.h"
#include <algorithm>
#include <numeric>

namespace dembridge::dem
{
namespace
{
/// The 21 low bits of v spread to every third bit (bit i -> bit 3 i).
std::uint64_t spread_bits(std::uint64_t v)
{
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

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

std::vector<std::size_t> morton_order(const std::vector<Vec3>& points)
{
  const std::size_t n = points.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  if (n < 2)
    return order;
  Vec3 lo = points[0], hi = points[0];
  for (const auto& x : points)
    lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const double side = (hi - lo).maxCoeff();
  if (!(side > 0))
    return order;
  // a cube, so that the curve's cells are cubes: its first splits cut the longest axis
  const double scale = double((1u << 21) - 1) / side;
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::uint64_t code = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double q = std::clamp((points[i][d] - lo[d]) * scale, 0.0, double((1u << 21) - 1));
      code |= spread_bits(std::uint64_t(q)) << (2 - d); // x the highest bit of each triple
    }
    key[i] = code;
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
  permute(p.dof_mask, order), permute(p.prescribed_velocity, order);
  permute(p.prescribed_angular_velocity, order), permute(p.group_mask, order);
  permute(p.coordination, order), permute(p.id, order);
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
  renumber_particles(p, b, groups, morton_order(p.reference_position));
}
} // namespace dembridge::dem
