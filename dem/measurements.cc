#include "measurements.h"
#include <algorithm>

namespace dembridge::dem
{
namespace
{
Vec3 reference_centroid(const ParticleStore& p, const Group& g)
{
  Vec3 c = Vec3::Zero();
  for (int i : g.members)
    c += p.reference_position[i];
  return c / double(g.members.size());
}
} // namespace

AxialResponse axial_response(const ParticleStore& p, const Group& fixed_end,
                             const Group& loaded_end, int axis)
{
  AxialResponse r;
  r.axis = axis;
  Vec3 lo = p.reference_position[0], hi = lo;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    lo = lo.cwiseMin(p.reference_position[i] - Vec3::Constant(p.radius[i]));
    hi = hi.cwiseMax(p.reference_position[i] + Vec3::Constant(p.radius[i]));
  }
  const Vec3 extent = hi - lo;
  r.area = 1.0;
  for (int d = 0; d < 3; ++d)
    if (d != axis)
      r.area *= extent[d];
  const double dx =
      reference_centroid(p, loaded_end)[axis] - reference_centroid(p, fixed_end)[axis];
  r.gauge_length = std::abs(dx);
  if (!(r.gauge_length > 0))
    throw InputError("Measurements/modulus groups: the two end groups have the same position");
  const double du = mean_displacement(p, loaded_end)[axis] - mean_displacement(p, fixed_end)[axis];
  r.strain = du / dx; // dx carries the orientation: tension positive
  // reaction on the loaded end, oriented like dx (a pull on the + end is tension)
  r.force = total_force(p, loaded_end)[axis] * (dx > 0 ? 1.0 : -1.0);
  r.stress = r.force / r.area;
  r.youngs_modulus = r.strain != 0 ? r.stress / r.strain : 0.0;
  for (int d = 0; d < 3; ++d)
  {
    if (d == axis)
      continue;
    GroupSelection s;
    s.kind = GroupSelection::Kind::face;
    s.face_axis = d;
    s.face_upper = false;
    const Group low = select_group(p, "lateral-", s, "Measurements");
    s.face_upper = true;
    const Group high = select_group(p, "lateral+", s, "Measurements");
    const double width = reference_centroid(p, high)[d] - reference_centroid(p, low)[d];
    if (width > 0 && r.strain != 0)
    {
      const double lateral =
          (mean_displacement(p, high)[d] - mean_displacement(p, low)[d]) / width; // eq. 65
      r.poisson_ratio[d] = -lateral / r.strain;
    }
  }
  return r;
}
} // namespace dembridge::dem
