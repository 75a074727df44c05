#include "coupling/coupled_case.h"
#include "coupling/continuum_tensor.h"
#include "coupling/region_volume.h"
#include "dem/bonds/bond_model.h"
#include "dem/measurements/elasticity_tensor.h"
#include "dem/model/model.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace dembridge::coupling
{
namespace
{
using Kind = dem::ParticleSource::Kind;

Voigt6x6 from_matrix(const dem::Matrix6& m)
{
  Voigt6x6 C{};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      C[6 * i + j] = 0.5 * (m(i, j) + m(j, i));
  return C;
}

bool is_lattice(Kind k)
{
  return k == Kind::cubic || k == Kind::hcp || k == Kind::fcc;
}

/// Linear s or smooth 3 s^2 - 2 s^3 from 0 at t = 0 to 1 at t = T, then 1.
std::function<double(double)> make_ramp(double T, bool smooth)
{
  return [T, smooth](double t)
  {
    if (!(T > 0) || t >= T)
      return 1.0;
    const double s = std::max(0.0, t / T);
    return smooth ? s * s * (3.0 - 2.0 * s) : s;
  };
}
} // namespace

Voigt6x6 continuum_tensor(const CoupledCase& c)
{
  const std::string where = "Coupling/continuum tensor";
  const auto& p = c.particles.particles;
  // The closed form and the periodic cell are the bare lattice's: grain boundaries and weak
  // planes change the region's tensor (docs/microstructure.md), so the two sides would differ.
  if (c.particles.microstructure.enabled() &&
      (c.tensor == TensorSource::closed_form || c.tensor == TensorSource::periodic))
    throw std::runtime_error(
        where + ": the " +
        (c.tensor == TensorSource::closed_form ? "closed form" : "periodic cell") +
        " is the lattice's without the Microstructure section's grains and "
        "weak planes; use measured (the region's own tensor) or file");
  switch (c.tensor)
  {
  case TensorSource::closed_form:
    if (p.kind != Kind::cubic)
      throw std::runtime_error(where +
                               ": the closed form is the simple cubic lattice's "
                               "(Particles/source = cubic); use periodic (hcp, fcc) or measured "
                               "(random) for this packing");
    return from_matrix(dem::simple_cubic_stiffness(c.particles.bonds.material, p.radius));
  case TensorSource::periodic:
  {
    if (!is_lattice(p.kind))
      throw std::runtime_error(where + ": the periodic cell needs a lattice packing (cubic, hcp "
                                       "or fcc); use measured for a random packing");
    const auto cell = dem::lattice_cell(p.kind, p.radius);
    return from_matrix(dem::periodic_stiffness_tensor(cell, c.particles.bonds.material,
                                                      c.particles.bonds.contact_radius_multiplier)
                           .properties.stiffness);
  }
  case TensorSource::measured:
  {
    // the particle region's own packing, free of the run's groups and loads
    dem::CaseConfig bare = c.particles;
    bare.particles.keep = nullptr; // the whole box: the tensor of the packing, not of a shape
    bare.groups.clear();
    bare.loads.clear();
    bare.measure = {};
    const dem::Model model = dem::build_model(bare);
    dem::ElasticityMeasurementSettings s;
    s.core_period = dem::lattice_axis_periods(p.kind, p.radius);
    std::printf("coupling: measuring the continuum tensor on the particle region's packing "
                "(%zu particles, six static solves)\n",
                model.particles.size());
    std::fflush(stdout);
    return from_matrix(dem::measured_stiffness_tensor(model, s).properties.stiffness);
  }
  case TensorSource::file:
    return read_elasticity_json(c.tensor_file, "Coupling/tensor file");
  }
  return {};
}

int pulse_side(const CoupledCase& c)
{
  if (!c.pulse.enabled)
    return 0;
  const auto& g = c.settings.geometry;
  const int a = c.pulse.axis;
  const bool in_particles = c.pulse.centre > g.particle_lo[a] && c.pulse.centre < g.particle_hi[a];
  return in_particles ? -1 : +1;
}

double last_ramp_end(const CoupledCase& c)
{
  double t = c.settings.driven.empty() ? 0.0 : c.ramp_time;
  for (const auto& l : c.particles.loads)
    t = std::max(t, l.load.ramp_time);
  return t;
}

void set_particle_region(std::shared_ptr<const RegionVolume> region, HandshakeGeometry& g,
                         dem::ParticleSource& packing)
{
  g.region = region;
  g.particle_lo = region->lo();
  g.particle_hi = region->hi();
  packing.origin = region->lo();
  packing.box_size = region->hi() - region->lo();
  // Every centre inside the volume. (Keeping only centres a radius below the coupled surface, as
  // a box's lattice lies half a spacing below its faces, made the uniform-strain patch test
  // worse on a ball: 4.0 % against 2.4 % at R = 6 d, L = 2 d. A lattice cut by a curved surface
  // leaves a staircase whose missing bonds' midpoints lie at depths from 0 to about d, so the
  // exact cancellation of a box's faces (handshake.h) is not available; docs/coupling.md gives
  // the figures.)
  packing.keep = [region](const Vec3& x) { return region->contains(x); };
}

namespace
{
/// The handshake's geometry from the FE box and the particle box (or the region file).
void set_geometry(CoupledCase& c)
{
  auto& g = c.settings.geometry;
  const auto& p = c.particles.particles;
  if (c.continuum.mesh_source != fem::MeshSource::box)
    throw std::runtime_error("FEM/Mesh/source: a coupled run meshes the FE domain box itself "
                             "(source = box; the band needs cell faces on its planes)");
  if (!(is_lattice(p.kind) || p.kind == Kind::random))
    throw std::runtime_error("Particles/source: a coupled run fills its particle region "
                             "(Particles/origin and box size) with a packing: cubic, hcp, fcc "
                             "or random");
  for (int d = 0; d < 3; ++d)
  {
    g.domain_lo[d] = c.continuum.box_lower[d];
    g.domain_hi[d] = c.continuum.box_upper[d];
  }
  g.particle_lo = p.origin;
  g.particle_hi = p.origin + p.box_size;
  g.particle_radius = p.radius;
  if (!c.region_file.empty()) // every rank reads it (the FE mesh needs the weights everywhere)
    set_particle_region(std::make_shared<const RegionVolume>(
                            read_region_volume(c.region_file, "Coupling/particle region file")),
                        g, c.particles.particles);
  if (pulse_side(c) != 0)
  {
    const int a = c.pulse.axis;
    if (c.pulse.centre < g.domain_lo[a] || c.pulse.centre > g.domain_hi[a])
      throw std::runtime_error("Coupling/pulse centre: lies outside the FE domain");
  }
}

/// Supports with a value: driven boundaries along the ramp (the FE supports are held at 0).
void drive_valued_supports(CoupledCase& c)
{
  std::vector<fem::BoundaryConstraint> held;
  for (const auto& b : c.continuum.boundary_constraints)
  {
    if (b.value == 0)
    {
      held.push_back(b);
      continue;
    }
    DrivenBoundary d;
    d.boundary = b.boundary;
    d.components = b.components;
    const double value = b.value;
    const auto mask = b.components;
    d.displacement = [value, mask](const Vec3&)
    { return Vec3(mask[0] ? value : 0.0, mask[1] ? value : 0.0, mask[2] ? value : 0.0); };
    d.ramp = make_ramp(c.ramp_time, c.smooth_ramp);
    c.settings.driven.push_back(d);
  }
  c.continuum.boundary_constraints = held;
}

/// Every rank computes the tensor the same way (deterministic), so no broadcast is needed; the
/// measured one is solved on rank 0 and broadcast.
void set_continuum_tensor(CoupledCase& c, MPI_Comm comm)
{
  if (c.tensor != TensorSource::measured)
  {
    c.settings.tensor = continuum_tensor(c);
    return;
  }
  std::vector<double> C(36, 0.0);
  std::string error;
  if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    try
    {
      const auto t = continuum_tensor(c);
      C.assign(t.begin(), t.end());
    }
    catch (const std::exception& e)
    {
      error = e.what();
    }
  error = dealii::Utilities::MPI::broadcast(comm, error, 0);
  if (!error.empty())
    throw std::runtime_error(error);
  C = dealii::Utilities::MPI::broadcast(comm, C, 0);
  std::copy(C.begin(), C.end(), c.settings.tensor.begin());
}

/// The wave runs' initial pulse on both sides, at the discrete phase speed of the side it
/// starts in.
void start_pulse(const CoupledCase& c, CoupledProblem& problem)
{
  Pulse pulse;
  pulse.axis = c.pulse.axis;
  pulse.centre = c.pulse.centre;
  pulse.wavelength = c.pulse.wavelength;
  pulse.amplitude = c.pulse.amplitude;
  pulse.envelope = c.pulse.envelope;
  pulse.direction = c.pulse.direction;
  const int a = pulse.axis;
  const double C11 = c.settings.tensor[6 * a + a];
  const double speed = std::sqrt(C11 / c.continuum.density);
  const double h =
      pulse_side(c) > 0 ? c.settings.element_size[a] : 2 * c.particles.particles.radius;
  pulse.speed = discrete_phase_speed(speed, h, problem.time_step(), pulse.wavelength);
  const double dt = problem.time_step();
  problem.set_initial_state([&](const Vec3& X) { return pulse_displacement(pulse, X); },
                            [&](const Vec3& X) { return pulse_velocity(pulse, X, dt); });
}
} // namespace

std::unique_ptr<CoupledProblem> make_coupled_problem(CoupledCase& c, MPI_Comm comm)
{
  set_geometry(c);
  drive_valued_supports(c);
  set_continuum_tensor(c, comm);
  auto problem = std::make_unique<CoupledProblem>(c.settings, c.continuum, c.particles, comm);
  problem->setup();
  if (pulse_side(c) != 0)
    start_pulse(c, *problem);
  return problem;
}
} // namespace dembridge::coupling

namespace dembridge::coupling
{
std::vector<std::string> damage_setup_warnings(const CoupledCase& c, CoupledProblem& p)
{
  using dem::Vec3;
  std::vector<std::string> lines;
  if (c.particles.damage.law.mode == dem::FailureMode::none)
    return lines;
  auto text = [](const Vec3& v)
  {
    std::ostringstream s;
    s << v.x() << ", " << v.y() << ", " << v.z();
    return s.str();
  };
  const auto& g = p.handshake().geometry();
  const auto& src = c.particles.particles;
  if ((src.remove_box_max - src.remove_box_min).minCoeff() > 0)
  {
    // the part of the notch box inside the FE domain must lie in the particle box
    const Vec3 lo = src.remove_box_min.cwiseMax(g.domain_lo);
    const Vec3 hi = src.remove_box_max.cwiseMin(g.domain_hi);
    const double tol = 1e-9 * (g.domain_hi - g.domain_lo).norm();
    if ((hi - lo).minCoeff() > 0 &&
        ((lo - g.particle_lo).minCoeff() < -tol || (g.particle_hi - hi).minCoeff() < -tol))
      lines.push_back("Particles/remove box: the notch (" + text(lo) + " to " + text(hi) +
                      ") reaches outside the particle region (" + text(g.particle_lo) + " to " +
                      text(g.particle_hi) +
                      "); the continuum there is not notched and cannot "
                      "crack");
  }
  const auto& model = p.model();
  const auto& h = p.handshake();
  for (const auto& load : model.loads)
  {
    const auto& group = model.groups[load.group];
    std::size_t outside = 0;
    for (int i : group.members)
      outside += !h.in_particle_only(model.particles.reference_position[i]);
    if (outside > 0)
      lines.push_back("Load " + load.name + ": " + std::to_string(outside) + " of the " +
                      std::to_string(group.members.size()) + " particles of group '" + group.name +
                      "' lie in the handshake band, whose bonds are held elastic "
                      "and blended with the continuum; load the particle-only region (at least "
                      "a band width inside the particle box) where damage is to start");
  }
  return lines;
}
} // namespace dembridge::coupling
