#include "dem/model/groups.h"
#include <algorithm>
#include <sstream>

namespace dembridge::dem
{
std::pair<int, bool> parse_face(const std::string& t, const std::string& where)
{
  if (t.size() == 2 && t[0] >= 'x' && t[0] <= 'z' && (t[1] == '-' || t[1] == '+'))
    return {t[0] - 'x', t[1] == '+'};
  throw InputError(where + ": unknown face '" + t + "' (expected x-, x+, y-, y+, z- or z+)");
}

std::pair<Vec3, Vec3> reference_extent(const ParticleStore& p)
{
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3 r = Vec3::Constant(p.radius[i]);
    lo =
        i == 0 ? Vec3(p.reference_position[i] - r) : Vec3(lo.cwiseMin(p.reference_position[i] - r));
    hi =
        i == 0 ? Vec3(p.reference_position[i] + r) : Vec3(hi.cwiseMax(p.reference_position[i] + r));
  }
  return {lo, hi};
}

Vec3 mean_displacement(const ParticleStore& p, const Group& g)
{
  Vec3 sum = Vec3::Zero();
  for (int i : g.members)
    sum += p.position[i] - p.reference_position[i];
  return g.members.empty() ? sum : Vec3(sum / double(g.members.size()));
}

Vec3 total_force(const ParticleStore& p, const Group& g)
{
  Vec3 sum = Vec3::Zero();
  for (int i : g.members)
    sum += p.force[i];
  return sum;
}

namespace
{
/// A `nearest` point far outside the specimen (further than a tenth of its bounding box's
/// diagonal) is most likely a typo or the wrong unit (mm for m): refused with the distance.
void check_nearest_point(const ParticleStore& p, const Vec3& point, const std::string& where)
{
  if (p.size() == 0)
    return;
  const auto [lo, hi] = reference_extent(p);
  const double outside = (point - point.cwiseMax(lo).cwiseMin(hi)).norm();
  const double diagonal = (hi - lo).norm();
  if (!(outside > 0.1 * diagonal))
    return;
  std::ostringstream text;
  text.precision(4);
  text << where.substr(0, where.rfind('/')) << "/point: (" << point.x() << ", " << point.y()
       << ", " << point.z() << ") lies " << outside << " m outside the specimen, whose bounding box is ("
       << lo.x() << ", " << lo.y() << ", " << lo.z() << ") to (" << hi.x() << ", " << hi.y()
       << ", " << hi.z() << ") m (more than a tenth of its diagonal away; units are m)";
  throw InputError(text.str());
}
} // namespace

Group select_group(const ParticleStore& p, const std::string& name, const GroupSelection& s,
                   const std::string& where)
{
  Group g;
  g.name = name;
  const long n = long(p.size());
  using K = GroupSelection::Kind;
  switch (s.kind)
  {
  case K::all:
    for (long i = 0; i < n; ++i)
      g.members.push_back(int(i));
    break;
  case K::index:
    for (long i : s.indices)
    {
      const long k = i < 0 ? n + i : i;
      if (k < 0 || k >= n)
        throw InputError(where + ": particle index " + std::to_string(i) +
                         " is out of range (there are " + std::to_string(n) + " particles)");
      g.members.push_back(int(k));
    }
    break;
  case K::box:
    for (long i = 0; i < n; ++i)
    {
      const Vec3& x = p.position[i];
      if ((x.array() >= s.box_min.array()).all() && (x.array() <= s.box_max.array()).all())
        g.members.push_back(int(i));
    }
    break;
  case K::face:
  {
    if (n == 0)
      break;
    const int a = s.face_axis;
    const auto [lo, hi] = reference_extent(p);
    for (long i = 0; i < n; ++i)
    {
      const double x = p.reference_position[i][a];
      const double dist = s.face_upper ? hi[a] - x : x - lo[a];
      if (dist <= s.face_thickness * p.radius[i] * (1.0 + 1e-9))
        g.members.push_back(int(i));
    }
    break;
  }
  case K::nearest:
  {
    long best = -1;
    double best_d2 = 0;
    for (long i = 0; i < n; ++i)
      if (const double d2 = (p.reference_position[i] - s.point).squaredNorm();
          best < 0 || d2 < best_d2)
        best = i, best_d2 = d2;
    if (best >= 0)
      g.members.push_back(int(best));
    check_nearest_point(p, s.point, where);
    break;
  }
  }
  std::sort(g.members.begin(), g.members.end());
  g.members.erase(std::unique(g.members.begin(), g.members.end()), g.members.end());
  if (g.members.empty())
    throw InputError(where + ": group '" + name + "' selects no particle");
  return g;
}
} // namespace dembridge::dem
