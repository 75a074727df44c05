#include "dem/packing/packings.h"
#include "dem/packing/cell_list.h"
#include "dem/packing/packing_random.h"
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
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
  const std::size_t before = p.size();
  keep_particles(p, [&](const Vec3& x)
                 { return !((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()); });
  if (p.size() == before)
    throw InputError("Particles/remove box min: the remove box holds no particle centre");
  if (p.size() == 0)
    throw InputError("Particles/remove box min: the remove box holds every particle");
}
} // namespace

void keep_particles(ParticleStore& p, const std::function<bool(const Vec3&)>& keep)
{
  ParticleStore kept;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& x = p.position[i];
    if (!keep(x))
      continue;
    kept.add(x, p.radius[i], 1.0);
    kept.set_mass(kept.size() - 1, p.mass[i]);
    kept.reference_position.back() = p.reference_position[i];
  }
  p = std::move(kept);
}

namespace
{
std::string lower(std::string s)
{
  for (char& c : s)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Column of x, y, z, r named by a header line ("x, y, z, r" in any order; "radius" for r);
/// throws naming the line when a name is unknown, repeated or missing.
std::array<int, 4> header_columns(const std::string& line, const std::string& where)
{
  std::istringstream ss(line);
  std::array<int, 4> column{-1, -1, -1, -1};
  int n = 0;
  for (std::string name; ss >> name; ++n)
  {
    name = lower(name);
    const std::string known = "xyzr";
    const auto k = name == "radius"   ? 3
                   : name.size() == 1 ? known.find(name[0])
                                      : std::string::npos;
    if (k == std::string::npos)
      throw InputError(where + ": unknown column '" + name +
                       "' in the header (expected x, y, z and r, in any order)");
    if (column[k] >= 0)
      throw InputError(where + ": the header names column '" + name + "' twice");
    column[k] = n;
  }
  for (int k = 0; k < 4; ++k)
    if (column[k] < 0)
      throw InputError(where + ": the header lacks column '" + std::string(1, "xyzr"[k]) + "'");
  return column;
}

/// Refuses particles of a file that overlap by more than max_file_overlap of the smaller radius
/// (or sit at one place), naming the pair and their lines.
void check_file_overlaps(const ParticleStore& p, const std::vector<int>& line,
                         const std::string& name)
{
  double rmax = 0;
  for (double r : p.radius)
    rmax = std::max(rmax, r);
  try
  {
    CellList cells(p.position, 2.0 * rmax);
    cells.for_each_pair(
        p.position,
        [&](int i, int j)
        {
          const double d = (p.position[i] - p.position[j]).norm();
          const double smaller = std::min(p.radius[i], p.radius[j]);
          const std::string pair = "particles " + std::to_string(i) + " and " + std::to_string(j);
          const std::string lines =
              " (lines " + std::to_string(line[i]) + " and " + std::to_string(line[j]) + ")";
          if (d < 1e-6 * smaller)
            throw InputError(name + ": " + pair + " sit at the same position" + lines);
          const double overlap = (p.radius[i] + p.radius[j] - d) / smaller;
          if (overlap > max_file_overlap)
          {
            char amount[64];
            std::snprintf(amount, sizeof amount, "%.3g %%", 100 * overlap);
            throw InputError(name + ": " + pair + lines + " overlap by " + amount +
                             " of the smaller radius (at most " +
                             std::to_string(int(100 * max_file_overlap)) + " % is accepted)");
          }
        });
  }
  catch (const InputError& e)
  {
    const std::string what = e.what();
    throw InputError(what.rfind(name, 0) == 0 ? what : name + ": " + what);
  }
}
} // namespace

void read_particles(std::istream& in, const std::string& name, double density, ParticleStore& p)
{
  std::string line;
  int lineno = 0;
  std::array<int, 4> column{0, 1, 2, 3}; // x, y, z, r
  std::vector<int> line_of;
  bool header_allowed = true;
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
    const std::string where = name + ":" + std::to_string(lineno);
    std::istringstream ss(line);
    double v[4];
    int n = 0;
    while (n < 4 && ss >> v[n])
      ++n;
    if (n == 0 && header_allowed)
    {
      column = header_columns(line, where); // the first line that is no comment may name them
      header_allowed = false;
      continue;
    }
    header_allowed = false;
    std::string rest;
    if (n != 4 || (ss >> rest))
      throw InputError(where + ": expected four numbers 'x, y, z, r' (m)");
    const Vec3 x(v[column[0]], v[column[1]], v[column[2]]);
    if (!x.allFinite())
      throw InputError(where + ": the position must be finite");
    check_radius(v[column[3]], where);
    p.add(x, v[column[3]], density);
    line_of.push_back(lineno);
  }
  if (in.bad())
    throw InputError(name + ": reading the particle file failed");
  if (p.size() == 0)
    throw InputError(name + ": the particle file holds no particle");
  check_file_overlaps(p, line_of, name);
}

void read_particle_file(const std::string& path, double density, ParticleStore& p)
{
  // why: a directory opens as a stream on Linux and then reads as empty
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path + ": cannot read the particle file (it is a directory)");
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot open the particle file");
  read_particles(in, path, density, p);
}

void generate_particles(const ParticleSource& s, ParticleStore& p, int threads)
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
    r.predict_jamming = s.predict_jamming;
    r.threads = threads;
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
