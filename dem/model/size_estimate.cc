#include "dem/model/size_estimate.h"
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/packing/packings.h"
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace dembridge::dem
{
namespace
{
template <class Vector> constexpr double element(const Vector&)
{
  return double(sizeof(typename Vector::value_type));
}

/// Rows of a lattice axis: floor((L - 2r - offset) / spacing + 1e-9) + 1, as packings.cc lays
/// them, never negative.
double rows(double length, double r, double offset, double spacing)
{
  return std::max(0.0, std::floor((length - 2 * r - offset) / spacing + 1e-9) + 1);
}

/// Spheres of the lattice that packings.cc lays into the box: stacking 1 simple cubic, 2 HCP
/// (ABAB), 3 FCC (ABC); per layer phase, rows alternate their x offset in triangular layers.
double lattice_count(const Vec3& box, double r, int stacking)
{
  const bool triangular = stacking > 1;
  const double dx = 2 * r, dy = triangular ? std::sqrt(3.0) * r : 2 * r;
  const double dz = triangular ? 2.0 * std::sqrt(2.0 / 3.0) * r : 2 * r;
  const double layers = rows(box.z(), r, 0, dz);
  double total = 0;
  for (int phase = 0; phase < (triangular ? stacking : 1); ++phase)
  {
    // layers k < layers with k % stacking == phase
    const double n_layers =
        triangular ? std::max(0.0, std::floor((layers - 1 - phase) / stacking) + 1) : layers;
    const double ox = phase == 1 ? r : 0.0, oy = phase * r / std::sqrt(3.0);
    const double ny = rows(box.y(), r, oy, dy);
    const double even = std::ceil(ny / 2), odd = std::floor(ny / 2);
    const double per_layer = triangular ? even * rows(box.x(), r, ox, dx) +
                                              odd * rows(box.x(), r, ox + r, dx)
                                        : ny * rows(box.x(), r, 0, dx);
    total += n_layers * per_layer;
  }
  return total;
}

/// Bonds per particle of a lattice: half the neighbours within the contact reach
/// m (r_i + r_j) of the particle nearest the centre of a small block of the same lattice.
double lattice_bonds_per_particle(const ParticleSource& source, double multiplier)
{
  if (multiplier > 3) // a block would be large; count the centres in the reach sphere instead
    return 0.5 * 0.74 * 8 * multiplier * multiplier * multiplier;
  ParticleSource block = source;
  block.origin = Vec3::Zero();
  block.save_file.clear();
  block.remove_box_min = block.remove_box_max = Vec3::Zero(); // no notch in the sample block
  block.box_size = Vec3::Constant((4 * multiplier + 6) * source.radius);
  ParticleStore p;
  generate_particles(block, p);
  const Vec3 centre = 0.5 * block.box_size;
  std::size_t middle = 0;
  for (std::size_t i = 1; i < p.size(); ++i)
    if ((p.position[i] - centre).norm() < (p.position[middle] - centre).norm())
      middle = i;
  const double reach = 2 * multiplier * source.radius * (1 + 1e-9);
  int neighbours = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    neighbours += i != middle && (p.position[i] - p.position[middle]).norm() <= reach;
  return 0.5 * neighbours;
}

/// Non-blank lines that are not '#' comments: at most the particles of a file.
double particle_file_lines(const std::string& path)
{
  std::ifstream in(path);
  double lines = 0;
  for (std::string line; std::getline(in, line);)
  {
    const auto first = line.find_first_not_of(" \t\r");
    lines += first != std::string::npos && line[first] != '#';
  }
  return lines;
}

/// E[(R / mean)^3] of the random packing's radius distribution (uniform: 1 + s^2; normal,
/// truncated at 2 s: below 1 + 3 s^2).
double mean_cubed_radius_ratio(const ParticleSource& s)
{
  if (s.distribution == "uniform")
    return 1 + s.radius_spread * s.radius_spread;
  if (s.distribution == "normal")
    return 1 + 3 * s.radius_spread * s.radius_spread;
  return 1;
}
} // namespace

double stored_bytes_per_particle()
{
  const ParticleStore p;
  return element(p.position) + element(p.reference_position) + element(p.velocity) +
         element(p.angular_velocity) + element(p.orientation) + element(p.force) +
         element(p.torque) + element(p.radius) + element(p.mass) + element(p.inertia) +
         element(p.dof_mask) + element(p.group_mask) + element(p.coordination) + element(p.id);
}

double stored_bytes_per_bond()
{
  const BondStore b;
  return element(b.a) + element(b.b) + element(b.rest_length) + element(b.rest_axis) +
         element(b.kn) + element(b.ks) + element(b.ktor) + element(b.kben) +
         element(b.contact_fraction) + element(b.radius) + element(b.damping_force) +
         element(b.damping_moment) + element(b.model) + element(b.state) + element(b.force) +
         element(b.moment);
}

// Beyond the stores (the particle store twice its size: a vector filled by push_back holds up
// to twice its elements; the bond store once: bond formation reserves it, reordering swaps in
// exact copies one array at a time), measured on the 26,004-particle HCP specimen (docs/trust.md):
//  - explicit: dashpot resultants and slab partition per particle, the ParaView patches of a
//    snapshot (particle: one point, 30 floats; bond: two points, 10 floats per point), the
//    particle stresses, the bond pair list of bond formation and the slab order per bond;
//  - static: the 6 x 6 diagonal block, the free-DOF index and the CG vectors per particle; the
//    6 x 6 off-diagonal block twice (block matrix and the scaled sparse copy, value and index)
//    and the assembly's pair lists per bond.
double peak_bytes_per_particle(bool static_solver)
{
  const double stores = 2 * stored_bytes_per_particle();
  const double output = 400 + 72 + 200; // snapshot patches, stress tensor, histogram and slabs
  const double solver = static_solver ? 36 * 8 + 36 * 12 + 6 * 4 + 10 * 6 * 8 : 48 + 16;
  return stores + output + solver;
}

double peak_bytes_per_bond(bool static_solver)
{
  const double stores = stored_bytes_per_bond() + 24; // + the largest array's reorder copy
  const double output = 300;                 // snapshot patches
  const double formation = 8 + 16;           // pair list, cell list share
  const double solver = static_solver ? 36 * 8 + 2 * 36 * 12 + 4 * 8 : 12;
  return stores + output + formation + solver;
}

SizeEstimate estimate_size(const CaseConfig& c)
{
  SizeEstimate e;
  const auto& s = c.particles;
  const double m = c.bonds.contact_radius_multiplier;
  using K = ParticleSource::Kind;
  const bool valid_radius = s.radius > 0 && std::isfinite(s.radius);
  double bonds_per_particle = 0;
  switch (s.kind)
  {
  case K::row:
    e.key = "Particles/count";
    e.particles = std::max(0, s.count);
    bonds_per_particle = std::max(1.0, m);
    break;
  case K::file:
    e.key = "Particles/file";
    e.particles = particle_file_lines(s.file);
    bonds_per_particle = 6 * m * m * m; // at most 12 equal spheres touch one
    break;
  case K::cubic:
  case K::hcp:
  case K::fcc:
  {
    e.key = "Particles/radius";
    if (!valid_radius || !(s.box_size.minCoeff() >= 2 * s.radius) || !(m > 0))
      return e; // the build reports what is wrong
    const int stacking = s.kind == K::cubic ? 1 : s.kind == K::hcp ? 2 : 3;
    e.particles = lattice_count(s.box_size, s.radius, stacking);
    bonds_per_particle = lattice_bonds_per_particle(s, m);
    break;
  }
  case K::random:
  {
    e.key = "Particles/radius";
    if (!valid_radius || !(s.target_porosity < 1))
      return e;
    const double sphere = 4.0 / 3.0 * std::numbers::pi * std::pow(s.radius, 3) *
                          mean_cubed_radius_ratio(s);
    e.particles = (1 - s.target_porosity) * std::max(0.0, s.box_size.prod()) / sphere;
    bonds_per_particle = 0.5 * 6.8 * std::max(1.0, m * m * m);
    break;
  }
  }
  e.bonds = c.bonds.explicit_bonds.empty() ? e.particles * bonds_per_particle
                                           : double(c.bonds.explicit_bonds.size());
  const bool static_solver = c.run.static_solver;
  e.bytes = e.particles * peak_bytes_per_particle(static_solver) +
            e.bonds * peak_bytes_per_bond(static_solver);
  return e;
}

void check_fits_in_memory(const SizeEstimate& e, double available)
{
  if (!(available > 0) || e.bytes <= available)
    return;
  std::ostringstream text;
  text.precision(3);
  text << e.key << ": the case would make about " << e.particles << " particles and " << e.bonds
       << " bonds, needing about " << human_bytes(e.bytes) << " of memory; this machine has "
       << human_bytes(available) << " available";
  throw InputError(text.str());
}
} // namespace dembridge::dem
