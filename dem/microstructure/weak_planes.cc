#include "dem/microstructure/weak_planes.h"
#include <algorithm>
#include <cmath>
#include <sstream>

namespace dembridge::dem
{
namespace
{
std::string number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}
} // namespace

PlaneCrossing crossed_planes(const WeakPlaneSet& set, const Vec3& xa, const Vec3& xb)
{
  PlaneCrossing c;
  const double sa = set.normal.dot(xa), sb = set.normal.dot(xb);
  for (std::size_t m = 0; m < set.offsets.size(); ++m)
  {
    const double o = set.offsets[m];
    long crossed;
    if (set.spacing > 0)
      crossed = std::abs(long(std::floor((sb - o) / set.spacing)) -
                         long(std::floor((sa - o) / set.spacing)));
    else
      crossed = (sa < o) != (sb < o);
    if (crossed > 0 && c.offset < 0)
      c.offset = int(m);
    c.count += crossed;
  }
  return c;
}

void check_weak_planes(WeakPlaneSet& set, double d, const std::string& where)
{
  const double length = set.normal.norm();
  if (!(length > 0) || !set.normal.allFinite())
    throw InputError(where + "weak plane normal: must be a non-zero vector");
  set.normal /= length;
  if (set.offsets.empty())
    throw InputError(where + "weak plane offsets: weak planes need at least one offset (m)");
  if (set.spacing < 0 || !std::isfinite(set.spacing))
    throw InputError(where + "weak plane spacing: must not be negative (0: each plane once)");
  if (set.spacing > 0 && set.spacing < d)
    throw InputError(where + "weak plane spacing: " + number(set.spacing) +
                     " m is below the particle spacing (" + number(d) +
                     " m): a bond would cross more than one plane");
  // planes closer than a particle spacing overlap: a bond may cross both, and which one it
  // belongs to is a matter of where the particles happen to sit
  std::vector<double> at = set.offsets;
  if (set.spacing > 0)
    for (double& o : at)
      o -= set.spacing * std::floor(o / set.spacing); // position within one period
  std::sort(at.begin(), at.end());
  for (std::size_t m = 0; m < at.size(); ++m)
  {
    const bool last = m + 1 == at.size();
    if (last && (set.spacing == 0 || at.size() == 1))
      break;
    const double next = last ? at[0] + set.spacing : at[m + 1]; // a family wraps round
    if (next - at[m] < d)
      throw InputError(where + "weak plane offsets: the planes at " + number(at[m]) + " and " +
                       number(next) + " m" + (set.spacing > 0 ? " (within one spacing)" : "") +
                       " are closer than the particle spacing (" + number(d) + " m): they overlap");
  }
}
} // namespace dembridge::dem
