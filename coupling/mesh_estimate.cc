#include "coupling/mesh_estimate.h"
#include "coupling/coupled_mesh.h"
#include "coupling/handshake.h"
#include <algorithm>

namespace dembridge::coupling
{
ContinuumMeshSize estimate_continuum_mesh(const CoupledCase& c)
{
  // the geometry as make_coupled_problem sets it (coupled_case.cc)
  HandshakeGeometry g = c.settings.geometry;
  const auto& p = c.particles.particles;
  for (int d = 0; d < 3; ++d)
  {
    g.domain_lo[d] = c.continuum.box_lower[d];
    g.domain_hi[d] = c.continuum.box_upper[d];
  }
  g.particle_lo = p.origin;
  g.particle_hi = p.origin + p.box_size;
  g.particle_radius = p.radius;
  if (!c.region_file.empty())
    g.region = std::make_shared<const RegionVolume>(
        read_region_volume(c.region_file, "Coupling/particle region file"));
  const Handshake h(g);
  const auto& s = c.settings;
  if (!(s.element_size.minCoeff() > 0) || !(s.band_element_size > 0))
    return {};
  // Too many cells along an axis to list: each interval between band planes has about its
  // length over the smallest size (rounded up) cells, at most.
  const double smallest = std::min(s.element_size.minCoeff(), s.band_element_size);
  const Vec3 length = g.domain_hi - g.domain_lo;
  ContinuumMeshSize size{1, 3};
  if (length.maxCoeff() / smallest > 1e6)
  {
    for (int d = 0; d < 3; ++d)
    {
      const double n = std::ceil(length[d] / smallest) + 5; // rounding up in 5 intervals at most
      size.cells *= n, size.dofs *= n + 1;
    }
    return size;
  }
  const auto steps = coupled_mesh_steps(h.geometry(), h.band_planes(), s.element_size,
                                        s.band_element_size, s.far_element_size, s.element_growth);
  for (const auto& axis : steps)
    size.cells *= double(axis.size()), size.dofs *= double(axis.size()) + 1;
  return size;
}
} // namespace dembridge::coupling
