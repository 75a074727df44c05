#include "dem/packing/packings.h"
#include "dem/packing/cell_list.h"
#include "dem/packing/packing_random.h"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dembridge::dem
{
namespace
{
void check_radius(double r, const std::string& where)
{
  if (!(r > 0) || !std::isfinite(r))
    throw InputError(where + ": particle radius must be positive (got " + std::to_string(r) +
                     " m)");
}

/// Layers of spheres along z. stacking 1: simple cubic (square layers); 2: HCP (triangular
/// layers ABAB); 3: FCC (triangular layers ABC). A, B and C are the three positions of a
/// triangular layer over the one below: B over the "up" hollows (r, r/sqrt3), C over the
/// "down" hollows (2r, 2r/sqrt3), equivalent to (0, 2r/sqrt3).
void lattice(const ParticleSource& s, ParticleStore& p, int stacking)
{
  const bool hcp = stacking > 1; // triangular layers
  const double r = s.radius;
  for (int d = 0; d < 3; ++d)
    if (s.box_size[d] < 2 * r)
      throw InputError("Particles/box size: the box (" + std::to_string(s.box_size[d]) +
                       " m along axis " + std::to_string(d) +
                       ") is smaller than one particle diameter (" + std::to_string(2 * r) + " m)");
  const double dx = 2 * r;
  const double dy = hcp ? std::sqrt(3.0) * r : 2 * r;
  const double dz = hcp ? 2.0 * std::sqrt(2.0 / 3.0) * r : 2 * r;
  const int nz = int(std::floor((s.box_size.z() - 2 * r) / dz + 1e-9)) + 1;
  for (int k = 0; k < nz; ++k)
  {
    const int phase = hcp ? k % stacking : 0; // 0: A, 1: B, 2: C
    const double ox = phase == 1 ? r : 0.0;
    const double oy = phase * r / std::sqrt(3.0);
    const int ny = int(std::floor((s.box_size.y() - 2 * r - oy) / dy + 1e-9)) + 1;
    for (int j = 0; j < ny; ++j)
    {
      const double rx = ox + (hcp && (j % 2) ? r : 0.0);
      const int nx = int(std::floor((s.box_size.x() - 2 * r - rx) / dx + 1e-9)) + 1;
      for (int i = 0; i < nx; ++i)
        p.add(s.origin + Vec3(r + rx + i * dx, r + oy + j * dy, r + k * dz), r, s.density);
    }
  }
}
/// Removes the particles whose centres lie inside the source's remove box (a notch cut before
/// bonding); nothing while the box has no volume.
void remove_notch(const ParticleSource& s, ParticleStore& p)
{
  const Vec3 lo = s.remove_box_min, hi = s.remove_box_max;
  if (lo.isZero() && hi.isZero())
    return;
  if (!(hi.array() > lo.array()).all())
    throw InputError("Particles/remove box max: must exceed 'remove box min' in every component");
  ParticleStore kept;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& x = p.position[i];
    if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all())
      continue;
    kept.add(x, p.radius[i], 1.0);
    kept.set_mass(kept.size() - 1, p.mass[i]);
    kept.reference_position.back() = p.reference_position[i];
  }
  if (kept.size() == p.size())
    throw InputError("Particles/remove box min: the remove box holds no particle centre");
  if (kept.size() == 0)
    throw InputError("Particles/remove box min: the remove box holds every particle");
  p = std::move(kept);
}
} // namespace

void read_particle_file(const std::string& path, double density, ParticleStore& p)
{
  // why: a directory opens as a stream on Linux and then reads as empty
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path + ": cannot read the particle file (it is a directory)");
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot open the particle file");
  std::string line;
  int lineno = 0;
  while (std::getline(in, line))
  {
    ++lineno;
    const auto hash = line.find('#');
    if (hash != std::string::npos)
      line.erase(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    for (char& c : line)
      if (c == ',' || c == ';')
        c = ' ';
    std::istringstream ss(line);
    double v[4];
    int n = 0;
    while (n < 4 && ss >> v[n])
      ++n;
    if (n == 0 && p.size() == 0 && lineno == 1)
      continue; // header line
    std::string rest;
    if (n != 4 || (ss >> rest))
      throw InputError(path + ":" + std::to_string(lineno) +
                       ": expected four numbers 'x, y, z, r' (m)");
    check_radius(v[3], path + ":" + std::to_string(lineno));
    p.add(Vec3(v[0], v[1], v[2]), v[3], density);
  }
  if (in.bad())
    throw InputError(path + ": reading the particle file failed");
  if (p.size() == 0)
    throw InputError(path + ": the particle file holds no particle");
}

void generate_particles(const ParticleSource& s, ParticleStore& p)
{
  if (!(s.density > 0))
    throw InputError("Particles/density: must be positive (got " + std::to_string(s.density) +
                     " kg/m^3)");
  using K = ParticleSource::Kind;
  switch (s.kind)
  {
  case K::row:
  {
    if (s.count < 1)
      throw InputError("Particles/count: a row needs at least one particle");
    if (!s.radii.empty() && int(s.radii.size()) != s.count)
      throw InputError("Particles/radii: " + std::to_string(s.radii.size()) + " radii given for " +
                       std::to_string(s.count) + " particles");
    if (!(s.direction.norm() > 0))
      throw InputError("Particles/direction: must be a non-zero vector");
    const Vec3 dir = s.direction.normalized();
    double pos = 0;
    for (int i = 0; i < s.count; ++i)
    {
      const double r = s.radii.empty() ? s.radius : s.radii[i];
      check_radius(r, "Particles/" + std::string(s.radii.empty() ? "radius" : "radii"));
      if (i > 0)
      {
        const double rprev = s.radii.empty() ? s.radius : s.radii[i - 1];
        pos += s.spacing > 0 ? s.spacing : rprev + r;
      }
      p.add(s.origin + pos * dir, r, s.density);
    }
    break;
  }
  case K::file:
    read_particle_file(s.file, s.density, p);
    break;
  case K::cubic:
  case K::hcp:
  case K::fcc:
    check_radius(s.radius, "Particles/radius");
    lattice(s, p, s.kind == K::cubic ? 1 : s.kind == K::hcp ? 2 : 3);
    break;
  case K::random:
  {
    RandomPackingSettings r;
    r.box_size = s.box_size;
    r.mean_radius = s.radius;
    using D = RandomPackingSettings::Distribution;
    if (s.distribution == "mono")
      r.distribution = D::mono;
    else if (s.distribution == "uniform")
      r.distribution = D::uniform;
    else if (s.distribution == "normal")
      r.distribution = D::normal;
    else
      throw InputError("Particles/distribution: unknown '" + s.distribution +
                       "' (expected mono, uniform or normal)");
    r.radius_spread = s.radius_spread;
    r.seed = s.seed;
    r.target_porosity = s.target_porosity;
    generate_random_packing(r, s.density, p);
    for (auto& x : p.position)
      x += s.origin;
    for (std::size_t i = 0; i < p.size(); ++i)
      p.reference_position[i] = p.position[i];
    break;
  }
  }
  remove_notch(s, p);
  // Overlapping particles (centres closer than 1e-6 of the smaller radius) are an input error.
  double rmax = 0;
  for (double r : p.radius)
    rmax = std::max(rmax, r);
  CellList cells(p.position, 2.0 * rmax);
  cells.for_each_pair(p.position,
                      [&](int i, int j)
                      {
                        const double d = (p.position[i] - p.position[j]).norm();
                        if (d < 1e-6 * std::min(p.radius[i], p.radius[j]))
                          throw InputError(
                              (s.kind == K::file ? s.file + ": particles " : "particles ") +
                              std::to_string(i) + " and " + std::to_string(j) +
                              " sit at the same position");
                      });
  // why: after the checks, so that bad input leaves no packing file behind
  if (!s.save_file.empty())
    write_particle_file(s.save_file, p);
}
} // namespace dembridge::dem
