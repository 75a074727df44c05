// Particles/specimen volume (specimen_volume.h): the packing's box from the gmsh volume, and the
// test that keeps a sphere wholly inside it.
#include "app/input/specimen_volume.h"
#include "coupling/region_volume.h"
#include "dem/core/particle_store.h"
#include "dem/packing/packings.h"

#include <memory>
#include <sstream>

namespace dembridge::app
{
namespace
{
const std::string key = "Particles/specimen volume";

std::string metres(double x)
{
  std::ostringstream s;
  s << x << " m";
  return s.str();
}

/// The volume's bounding box must take two particle diameters along every axis: a thinner one
/// holds at most one sphere across, no specimen.
void check_thickness(const coupling::RegionVolume& volume, const std::string& file, double r)
{
  const dem::Vec3 size = volume.hi() - volume.lo();
  for (int d = 0; d < 3; ++d)
    if (size[d] < 4 * r * (1 - 1e-9))
      throw dem::InputError(key + ": '" + file + "' is " + metres(size[d]) + " thick along " +
                            std::string(1, char('x' + d)) +
                            ", thinner than two particle diameters (" + metres(4 * r) +
                            " for Particles/radius = " + metres(r) + ")");
}

/// A lattice is cheap to generate: count the spheres the cut keeps, so that an empty specimen is
/// refused here with the file's name (a random packing is generated once, by the run).
void check_lattice_keeps_a_sphere(const dem::ParticleSource& source, const std::string& file)
{
  using K = dem::ParticleSource::Kind;
  if (source.kind != K::cubic && source.kind != K::hcp && source.kind != K::fcc)
    return;
  dem::ParticleSource lattice = source;
  lattice.save_file.clear();
  dem::ParticleStore p;
  dem::generate_particles(lattice, p);
  for (const auto& x : p.position)
    if (source.keep(x))
      return;
  throw dem::InputError(key + ": '" + file + "' holds no whole sphere of the " +
                        std::to_string(p.size()) + " the lattice puts in its bounding box (" +
                        "a sphere is kept when it lies wholly inside the volume)");
}
} // namespace

dem::Vec3 apply_specimen_volume(dem::ParticleSource& source, const std::string& file)
{
  using K = dem::ParticleSource::Kind;
  if (source.kind == K::row || source.kind == K::file)
    throw dem::InputError(key + ": '" + file +
                          "' cuts a generated packing (Particles/source = cubic, hcp, fcc or "
                          "random), not a " +
                          (source.kind == K::row ? "row" : "particle file"));
  auto volume = std::make_shared<coupling::RegionVolume>();
  try
  {
    *volume = coupling::read_region_volume(file, key);
  }
  catch (const dem::InputError&)
  {
    throw;
  }
  catch (const std::exception& e) // the reader's messages already name the key and the file
  {
    throw dem::InputError(e.what());
  }
  const double r = source.radius;
  check_thickness(*volume, file, r);
  source.origin = volume->lo();
  source.box_size = volume->hi() - volume->lo();
  // Only distances up to r matter: beyond that reach the sphere is clear of every facet.
  auto surface = std::make_shared<coupling::SurfaceDistance>(volume->boundary(), r);
  const double clearance = r * (1 - 1e-9); // a sphere touching a flat face from inside is in
  source.keep = [volume, surface, clearance](const dem::Vec3& x)
  { return volume->contains(x) && surface->distance(x) >= clearance; };
  check_lattice_keeps_a_sphere(source, file);
  // the cross-section normal to each axis: the volume over its length along the axis
  dem::Vec3 section_area;
  for (int d = 0; d < 3; ++d)
    section_area[d] = volume->volume() / source.box_size[d];
  return section_area;
}
} // namespace dembridge::app
