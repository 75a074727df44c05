#include "coupling/handshake.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dembridge::coupling
{
namespace
{
std::string text(const Vec3& v)
{
  std::ostringstream s;
  s << v.x() << ", " << v.y() << ", " << v.z();
  return s.str();
}
} // namespace

Handshake::Handshake(const HandshakeGeometry& geometry) : g_(geometry)
{
  if (g_.region)
  {
    g_.particle_lo = g_.region->lo();
    g_.particle_hi = g_.region->hi();
  }
  const HandshakeGeometry& g = g_;
  const double scale = (g.domain_hi - g.domain_lo).norm();
  const double tol = 1e-9 * scale;
  if (!((g.domain_hi - g.domain_lo).minCoeff() > 0))
    throw std::runtime_error("FEM/Mesh/box upper: the FE domain box is empty (min " +
                             text(g.domain_lo) + ", max " + text(g.domain_hi) + ")");
  if (!((g.particle_hi - g.particle_lo).minCoeff() > 0))
    throw std::runtime_error("Particles/box size: the particle region is empty");
  const std::string region_key =
      g.region ? "Coupling/particle region file" : std::string("Particles/origin");
  for (int d = 0; d < 3; ++d)
    if (g.particle_lo[d] < g.domain_lo[d] - tol || g.particle_hi[d] > g.domain_hi[d] + tol)
      throw std::runtime_error(region_key + ": the particle region (" + text(g.particle_lo) +
                               " to " + text(g.particle_hi) + ") lies outside the FE domain (" +
                               text(g.domain_lo) + " to " + text(g.domain_hi) + ")");
  if (!(g.particle_radius > 0))
    throw std::runtime_error("Coupling: the particle radius must be positive");
  const double diameter = 2 * g.particle_radius;
  if (!(g.band_width >= 2 * diameter * (1 - 1e-9)))
  {
    std::ostringstream s;
    s << "Coupling/band width: " << g.band_width << " m is thinner than two particle diameters ("
      << 2 * diameter << " m)";
    throw std::runtime_error(s.str());
  }
  if (!(g.weight_floor > 0 && g.weight_floor < 0.5))
    throw std::runtime_error("Coupling/weight floor: must lie in (0, 0.5)");
  bool any = false;
  for (int d = 0; d < 3; ++d)
  {
    coupled_[2 * d] = g.particle_lo[d] > g.domain_lo[d] + tol;
    coupled_[2 * d + 1] = g.particle_hi[d] < g.domain_hi[d] - tol;
    any = any || coupled_[2 * d] || coupled_[2 * d + 1];
    const int n = int(coupled_[2 * d]) + int(coupled_[2 * d + 1]);
    if (!g.region && n > 0 && (g.particle_hi[d] - g.particle_lo[d]) < n * g.band_width)
      throw std::runtime_error("Coupling/band width: the band (" + std::to_string(g.band_width) +
                               " m) does not fit in the particle region along " +
                               std::string(1, "xyz"[d]) + " (no particle-only region left)");
  }
  if (g.region)
  {
    // the coupled surface: boundary triangles not lying on a face of the domain
    std::vector<Triangle> coupled;
    for (const auto& t : g.region->boundary())
    {
      bool on_domain = false;
      for (int d = 0; d < 3 && !on_domain; ++d)
        for (const double plane : {g.domain_lo[d], g.domain_hi[d]})
          on_domain =
              on_domain || (std::abs(t[0][d] - plane) < tol && std::abs(t[1][d] - plane) < tol &&
                            std::abs(t[2][d] - plane) < tol);
      if (!on_domain)
        coupled.push_back(t);
    }
    any = !coupled.empty();
    surface_ = SurfaceDistance(std::move(coupled), 1.5 * g.band_width);
  }
  if (!any)
    throw std::runtime_error(region_key + ": the particle region fills the FE domain "
                                          "(no face inside it to couple through)");
}

double Handshake::depth(const Vec3& x) const
{
  if (g_.region)
  {
    const double s = surface_.distance(x);
    return g_.region->contains(x) ? s : -s;
  }
  double s = std::numeric_limits<double>::infinity();
  for (int d = 0; d < 3; ++d)
  {
    if (coupled_[2 * d])
      s = std::min(s, x[d] - g_.particle_lo[d]);
    if (coupled_[2 * d + 1])
      s = std::min(s, g_.particle_hi[d] - x[d]);
  }
  return s;
}

bool Handshake::in_particle_box(const Vec3& x) const
{
  if (g_.region)
    return g_.region->contains(x);
  for (int d = 0; d < 3; ++d)
    if (x[d] < g_.particle_lo[d] || x[d] > g_.particle_hi[d])
      return false;
  return true;
}

double Handshake::depth_inside(const Vec3& x) const
{
  return g_.region ? surface_.distance(x) : depth(x);
}

double Handshake::alpha(const Vec3& x) const
{
  if (!in_particle_box(x))
    return 0.0;
  return std::clamp(depth_inside(x) / g_.band_width, 0.0, 1.0); // eq. 6: linear ramp
}

bool Handshake::in_band(const Vec3& x) const
{
  if (!in_particle_box(x))
    return false;
  const double s = depth_inside(x), tol = 1e-9 * g_.band_width;
  return s >= -tol && s <= g_.band_width + tol;
}

bool Handshake::in_particle_only(const Vec3& x) const
{
  return in_particle_box(x) && depth_inside(x) > g_.band_width * (1 + 1e-9);
}

double Handshake::particle_mass_share(const Vec3& x) const
{
  if (!in_particle_box(x))
    return 0.0;
  const double s = depth_inside(x);
  if (s < 0)
    return 0.0;
  if (s > g_.band_width)
    return 1.0;
  const double f = g_.weight_floor;
  return f + (1 - 2 * f) * std::clamp(s / g_.band_width, 0.0, 1.0);
}

double Handshake::fe_mass_weight(const Vec3& x) const
{
  const double share = particle_mass_share(x);
  return share == 1.0 ? g_.weight_floor : 1.0 - share;
}

std::pair<Vec3, Vec3> Handshake::particle_only_box() const
{
  Vec3 lo = g_.particle_lo, hi = g_.particle_hi;
  const double inset = g_.band_width;
  for (int d = 0; d < 3; ++d)
  {
    if (coupled_[2 * d])
      lo[d] += inset;
    if (coupled_[2 * d + 1])
      hi[d] -= inset;
  }
  return {lo, hi};
}

std::array<std::vector<double>, 3> Handshake::band_planes() const
{
  std::array<std::vector<double>, 3> planes;
  const double L = g_.band_width;
  for (int d = 0; d < 3; ++d)
  {
    if (g_.region)
    {
      if (coupled_[2 * d] || coupled_[2 * d + 1])
        planes[d] = {g_.particle_lo[d], g_.particle_hi[d]};
      continue;
    }
    if (coupled_[2 * d])
      planes[d].insert(planes[d].end(), {g_.particle_lo[d], g_.particle_lo[d] + L});
    if (coupled_[2 * d + 1])
      planes[d].insert(planes[d].end(), {g_.particle_hi[d] - L, g_.particle_hi[d]});
  }
  return planes;
}
} // namespace dembridge::coupling
