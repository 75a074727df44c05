#include "dem/measurements/failure_measurements.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dembridge::dem
{
DamageLayers damage_layers(const ParticleStore& p, const BondStore& b, const Vec3& lo,
                           const Vec3& hi, int axis, int n)
{
  if (n < 1 || axis < 0 || axis > 2)
    throw std::invalid_argument("damage_layers: needs n >= 1 slabs along axis 0, 1 or 2");
  DamageLayers l;
  l.axis = axis;
  const double h = (hi[axis] - lo[axis]) / n;
  for (int j = 0; j <= n; ++j)
    l.edges.push_back(lo[axis] + j * h);
  l.bonds.assign(n, 0);
  l.broken.assign(n, 0);
  long total_broken = 0;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const double mid =
        0.5 * (p.reference_position[b.a[k]][axis] + p.reference_position[b.b[k]][axis]);
    const int j = h > 0 ? std::clamp(int(std::floor((mid - lo[axis]) / h)), 0, n - 1) : 0;
    ++l.bonds[j];
    if (b.state[k] == BondState::broken)
      ++l.broken[j], ++total_broken;
  }
  for (int j = 0; j < n; ++j)
    l.broken_fraction.push_back(l.bonds[j] > 0 ? double(l.broken[j]) / double(l.bonds[j]) : 0.0);
  if (total_broken > 0)
    for (int j = 0; j < n; ++j)
    {
      const long pair = l.broken[j] + (j + 1 < n ? l.broken[j + 1] : 0);
      const double share = double(pair) / double(total_broken);
      if (share > l.localisation)
        l.localisation = share, l.band = j;
    }
  return l;
}

PeakLoad peak_of(const std::vector<double>& load, const std::vector<double>& displacement)
{
  if (load.size() != displacement.size())
    throw std::invalid_argument("peak_of: load and displacement histories differ in length");
  PeakLoad peak;
  for (std::size_t i = 0; i < load.size(); ++i)
    if (peak.index < 0 || std::abs(load[i]) > std::abs(peak.load))
      peak = {load[i], displacement[i], long(i)};
  return peak;
}

PeakLoad limit_of(const std::vector<double>& load, const std::vector<double>& displacement)
{
  if (load.size() != displacement.size())
    throw std::invalid_argument("limit_of: load and displacement histories differ in length");
  PeakLoad limit;
  for (std::size_t i = 0; i < load.size(); ++i)
  {
    if (limit.index >= 0 && std::abs(load[i]) < 0.5 * std::abs(limit.load))
      break;
    if (limit.index < 0 || std::abs(load[i]) > std::abs(limit.load))
      limit = {load[i], displacement[i], long(i)};
  }
  return limit;
}

std::size_t records_before(const std::vector<double>& load, double fraction)
{
  double peak = 0;
  for (double f : load)
    peak = std::max(peak, std::abs(f));
  std::size_t n = 0;
  while (n < load.size() && std::abs(load[n]) < fraction * peak)
    ++n;
  return n;
}
} // namespace dembridge::dem
