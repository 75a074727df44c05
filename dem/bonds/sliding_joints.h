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
// Grain boundaries may slide too: two particles of two grains g and h (ParticleStore::grain) meet
// on the grains' boundary, the plane that bisects their seeds S_g and S_h (a Voronoi cell's
// face: columnar_grains.h), whose normal from g's side to h's is
//   n_gh = (S_h - S_g) / |S_h - S_g|
// with the boundaries' own friction coefficient mu_gb. A pair that lies across a weak plane as
// well meets on the plane (the weak-plane class wins, as for the bonds).
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
  /// Each grain's seed S_g (columnar_grains.h), m; empty: the grain boundaries do not slide.
  std::vector<Vec3> grain_seed;
  double boundary_friction = 0; ///< mu_gb >= 0: Coulomb's coefficient on a grain boundary

  bool has_boundaries() const { return !grain_seed.empty(); }
  /// n_gh of the header: from grain g's side of their boundary to grain h's.
  Vec3 boundary_normal(std::int32_t g, std::int32_t h) const
  {
    return (grain_seed[std::size_t(h)] - grain_seed[std::size_t(g)]).normalized();
  }

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
