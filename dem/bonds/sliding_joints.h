#pragma once
// The planes on which broken smooth joints slide (contacts/joint_contact.h): the weak planes'
// set (microstructure/weak_planes.h: the planes N.x = o_m, or a family of them every s along N)
// and the joints' friction coefficient mu_j. Two particles lie on two sides of a plane when
// their side indices differ:
//   side(x) = sum_m [ s > 0 ? floor((N.x - o_m) / s) : (N.x >= o_m ? 1 : 0) ]
// Each term steps up by one at each of its planes and nowhere else, so side(x_b) - side(x_a) is
// the number of planes between x_a and x_b (signed along N), and a bond crosses a plane exactly
// when its ends' sides differ (weak_planes.h: the bonds' classes). Sides are read at the
// reference positions, where the classes were read: a particle keeps its side while it slides.
#include "dem/core/types.h"
#include <cmath>
#include <vector>

namespace dembridge::dem
{
struct SlidingJoints
{
  Vec3 normal = Vec3::UnitX(); ///< N, unit
  std::vector<double> offsets; ///< o_m, m
  double spacing = 0;          ///< s, m (0: each plane once)
  double friction = 0;         ///< mu_j >= 0: Coulomb's coefficient on the plane

  /// side(x) of the header.
  long side(const Vec3& x) const
  {
    const double h = normal.dot(x);
    long sum = 0;
    for (double o : offsets)
      sum += spacing > 0 ? long(std::floor((h - o) / spacing)) : long(h >= o);
    return sum;
  }
};
} // namespace dembridge::dem
