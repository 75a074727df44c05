#include "coupling/blending.h"
#include <algorithm>
#include <stdexcept>

namespace dembridge::coupling
{
std::vector<int> find_interface_particles(const Handshake& h, const dem::ParticleStore& p)
{
  std::vector<int> interface;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& x = p.reference_position[i];
    if (!h.in_particle_box(x))
      throw std::runtime_error("Coupling/particle region: particle " + std::to_string(i) +
                               " lies outside the particle region");
    if (h.in_band(x))
      interface.push_back(int(i));
  }
  if (interface.empty())
    throw std::runtime_error("Coupling/band width: no particle centre lies in the handshake band "
                             "(no interface particles)");
  if (interface.size() == p.size())
    throw std::runtime_error("Coupling/band width: every particle centre lies in the handshake "
                             "band (no particle-only region; narrow the band or enlarge the "
                             "particle region)");
  return interface;
}

ParticleBlending blend_particles(const Handshake& h, const std::vector<int>& interface,
                                 const std::vector<double>& interface_mass_weight,
                                 dem::ParticleStore& p, dem::BondStore& b)
{
  ParticleBlending r;
  r.interface = interface;
  r.mass_weight.assign(p.size(), 1.0);
  const double floor = 0.5 * h.geometry().weight_floor;
  for (std::size_t k = 0; k < interface.size(); ++k)
    r.mass_weight[interface[k]] = std::clamp(interface_mass_weight[k], floor, 1.0);
  r.inertia_weight = r.mass_weight;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const Vec3 mid = 0.5 * (p.reference_position[b.a[k]] + p.reference_position[b.b[k]]);
    const double a = h.alpha(mid); // eq. 7: internal forces weighted at the bond midpoint
    b.kn[k] *= a, b.ks[k] *= a, b.ktor[k] *= a, b.kben[k] *= a;
    b.damping_force[k] *= a, b.damping_moment[k] *= a;
    for (const int i : {b.a[k], b.b[k]})
      r.inertia_weight[i] = std::max(r.inertia_weight[i], a);
    if (a < 1.0)
    {
      r.band_bonds.push_back(k);
      r.band_bond_alpha.push_back(a);
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    p.mass[i] *= r.mass_weight[i]; // eq. 8: m_p -> w_p m_p
    p.inertia[i] *= r.inertia_weight[i];
  }
  return r;
}
} // namespace dembridge::coupling
