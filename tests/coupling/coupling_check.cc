// Physics checks of the coupled DEM-FE mode (coupling/): one check per ctest, chosen by the
// first argument. Each prints its numbers and the reference with the tolerance, and exits 1 if a
// check fails.
//   wave        a longitudinal pulse through the handshake band of a bar, both directions
//   band_mass   the blended masses of particles and continuum sum to the body's
//   ... (see main)
#include "coupling/coupled_case.h"
#include "coupling/coupled_problem.h"
#include "coupling/measurements.h"
#include "coupling/region_volume.h"
#include "dem/bonds/bond_model.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <numbers>
#include <string>

using namespace dembridge;
using coupling::Vec3;

namespace
{
int failures = 0;
std::string mesh_dir; ///< the build's meshes folder (argv[2] of the *_volume checks)

void check(const bool ok, const std::string& what)
{
  std::printf("%s: %s\n", ok ? "PASS" : "FAIL", what.c_str());
  failures += !ok;
}

// ------------------------------------------------------------------------------------------
// A bar of simple cubic PBM lattice (n x n particles across) along x: continuum on
// [0, fe_length], particles on [fe_length, fe_length + particle_length], the band inside the
// particle region.
struct Bar
{
  double radius = 0.005;
  int across = 1;         ///< particles across the bar (y and z)
  double fe_length = 0.8; ///< m
  double particle_length = 0.8;
  double band_width = 0.03;   ///< m
  double element_size = 0.01; ///< along x, m
  double density = 2500;      ///< kg/m^3 (of the continuum; the lattice scales its spheres)
  coupling::Tying tying = coupling::Tying::particle;
  coupling::ConstraintSolve solve = coupling::ConstraintSolve::exact;
  double fine_scale_damping = 0;
  double weight_floor = 0.1;

  double spacing() const { return 2 * radius; }
  double width() const { return across * spacing(); }

  dem::BondMaterial material() const
  {
    dem::BondMaterial m;
    m.model = dem::BondModel::parallel_bond;
    m.youngs_modulus = 4e9;
    m.poisson_ratio = 0.3;
    m.stiffness_ratio = 4.2;
    return m;
  }
  dem::BondStiffness bond() const
  {
    return dem::bond_stiffness(material(), spacing(), radius, radius);
  }
  /// Long-wave speed sqrt(C11 / rho) of the lattice and its continuum.
  double wave_speed() const { return std::sqrt(bond().kn / spacing() / density); }

  std::unique_ptr<coupling::CoupledProblem> make(MPI_Comm comm) const
  {
    dem::CaseConfig c;
    c.particles.kind = dem::ParticleSource::Kind::cubic;
    c.particles.radius = radius;
    c.particles.density = density;
    c.particles.scale_density_by_porosity = true; // m = rho d^3: the lattice weighs the continuum
    c.particles.box_size = Vec3(particle_length, width(), width());
    c.particles.origin = Vec3(fe_length, 0, 0);
    c.bonds.material = material();
    c.run.threads = 1;
    fem::Parameters fe;
    fe.density = density;
    fe.degree = 1;
    coupling::CouplingSettings s;
    s.geometry.domain_lo = Vec3::Zero();
    s.geometry.domain_hi = Vec3(fe_length + particle_length, width(), width());
    s.geometry.particle_lo = Vec3(fe_length, 0, 0);
    s.geometry.particle_hi = s.geometry.domain_hi;
    s.geometry.band_width = band_width;
    s.geometry.weight_floor = weight_floor;
    s.geometry.particle_radius = radius;
    s.element_size = Vec3(element_size, spacing(), spacing());
    s.band_element_size = element_size;
    const auto k = bond();
    s.tensor = coupling::simple_cubic_tensor(k.kn, k.ks, spacing());
    s.tying = tying;
    s.solve = solve;
    s.fine_scale_damping = fine_scale_damping;
    auto problem = std::make_unique<coupling::CoupledProblem>(s, fe, c, comm);
    problem->setup();
    return problem;
  }
};

struct WaveResult
{
  double reflected = 0, transmitted = 0, balance = 0, band = 0;
};

/// A pulse of dominant wavelength @p wavelength from one side through the band: the energy left
/// on the incident side once the pulse has passed (reflected) and on the other side
/// (transmitted), relative to the initial energy; the largest |E(t) - E_0| / E_0 on the way.
WaveResult wave_through_band(const Bar& bar, const double wavelength, const bool from_continuum,
                             MPI_Comm comm)
{
  auto problem = bar.make(comm);
  const double dt = problem->time_step();
  const double c = bar.wave_speed();
  const double band_lo = bar.fe_length + bar.radius, band_hi = band_lo + bar.band_width;
  coupling::Pulse pulse;
  pulse.wavelength = wavelength;
  pulse.amplitude = 1e-6;
  pulse.envelope = 1.0;
  double distance = 0;
  if (from_continuum)
  {
    pulse.centre = bar.fe_length - 4 * wavelength;
    pulse.direction = +1;
    pulse.speed = coupling::discrete_phase_speed(c, bar.element_size, dt, wavelength);
    distance = band_hi + 3.5 * wavelength - pulse.centre;
  }
  else
  {
    pulse.centre = band_hi + 4 * wavelength;
    pulse.direction = -1;
    pulse.speed = coupling::discrete_phase_speed(c, bar.spacing(), dt, wavelength);
    distance = pulse.centre - (band_lo - 3.5 * wavelength);
  }
  problem->set_initial_state([&](const Vec3& X) { return coupling::pulse_displacement(pulse, X); },
                             [&](const Vec3& X) { return coupling::pulse_velocity(pulse, X, dt); });
  const long steps = long(std::ceil(distance / c / dt));
  WaveResult r;
  double e0 = 0;
  for (long n = 0; n <= steps; ++n)
  {
    const bool record = n % 10 == 0 || n == steps;
    problem->step(record);
    if (!record)
      continue;
    const auto& e = problem->energies();
    const double total = e.dem_total() + e.fe_total();
    if (n == 0)
      e0 = e.initial;
    r.balance = std::max(r.balance, std::abs(total - e0) / e0);
  }
  const auto& e = problem->energies();
  r.reflected = (from_continuum ? e.fe_total() : e.dem_total()) / e0;
  r.transmitted = (from_continuum ? e.dem_total() : e.fe_total()) / e0;
  return r;
}

// ------------------------------------------------------------------------------------------
void check_wave(MPI_Comm comm)
{
  // Matched: FE nodes on the particle planes (h = d).
  Bar bar;
  const double lambda = 10 * bar.spacing();
  for (const bool from_continuum : {true, false})
  {
    const auto r = wave_through_band(bar, lambda, from_continuum, comm);
    std::printf("wave %s, lambda = 10 d, h = d: reflected %.3e, transmitted %.6f, "
                "energy balance %.3e\n",
                from_continuum ? "continuum -> particles" : "particles -> continuum", r.reflected,
                r.transmitted, r.balance);
    // measured: 3.02e-5 reflected both ways, reflected + transmitted = 1 to 1e-9, balance
    // 1.4e-10 and 3.1e-10 (a continuum mass left unweighted in the band: 5.7e-3 reflected)
    check(r.reflected < 1e-4, "reflected energy below 1e-4 of the incident");
    check(std::abs(r.reflected + r.transmitted - 1) < 1e-6,
          "reflected + transmitted = 1 within 1e-6");
    check(r.balance < 2e-9, "total energy conserved to 2e-9");
  }
}
// ------------------------------------------------------------------------------------------
// A cube of continuum, 16 d on a side, with a simple cubic particle block of 10 d inside it
// (box 3 d ... 13 d, particle centres on the planes 3.5 d ... 12.5 d): the band runs round all
// six faces.
struct Block
{
  double radius = 0.005;
  double element_size = 0.01; ///< h
  double band_width = 0.02;
  double density = 2500;
  double mass_damping = 0;
  /// A gmsh volume as the particle region instead of the box (meshes/region_sphere.geo: a ball
  /// of radius 10 d about (12 d, 12 d, 12 d), in a cube of 24 d).
  std::string region_file;
  double domain = 16; ///< the cube's side in spacings d
  /// The particle block across the whole cube in y and z (a slab 10 d thick): only its two x
  /// faces are coupled.
  bool slab = false;

  double spacing() const { return 2 * radius; }
  std::unique_ptr<coupling::CoupledProblem>
  make(MPI_Comm comm, std::vector<coupling::DrivenBoundary> driven = {}) const
  {
    const double d = spacing();
    Bar bar; // the same bonds
    bar.radius = radius;
    dem::CaseConfig c;
    c.particles.kind = dem::ParticleSource::Kind::cubic;
    c.particles.radius = radius;
    c.particles.density = density;
    c.particles.scale_density_by_porosity = true;
    c.particles.box_size = slab ? Vec3(10 * d, domain * d, domain * d) : Vec3::Constant(10 * d);
    c.particles.origin = slab ? Vec3(3 * d, 0, 0) : Vec3::Constant(3 * d);
    c.bonds.material = bar.material();
    c.run.threads = 1;
    fem::Parameters fe;
    fe.density = density;
    coupling::CouplingSettings s;
    s.geometry.domain_lo = Vec3::Zero();
    s.geometry.domain_hi = Vec3::Constant(domain * d);
    s.geometry.particle_lo = c.particles.origin;
    s.geometry.particle_hi = c.particles.origin + c.particles.box_size;
    s.geometry.band_width = band_width;
    s.geometry.particle_radius = radius;
    s.element_size = Vec3::Constant(element_size);
    s.band_element_size = element_size;
    const auto k = bar.bond();
    s.tensor = coupling::simple_cubic_tensor(k.kn, k.ks, d);
    s.mass_damping = mass_damping;
    s.driven = std::move(driven);
    if (!region_file.empty())
      coupling::set_particle_region(std::make_shared<const coupling::RegionVolume>(
                                        coupling::read_region_volume(region_file, "region")),
                                    s.geometry, c.particles);
    auto problem = std::make_unique<coupling::CoupledProblem>(s, fe, c, comm);
    problem->setup();
    return problem;
  }
};

// ------------------------------------------------------------------------------------------
/// The coupled model's mass: the particles' blended masses w_p m_p plus the continuum's lumped
/// masses weighted by w_M (one component per node), every rank's share summed.
double blended_mass(coupling::CoupledProblem& problem, MPI_Comm comm)
{
  double particles = 0;
  for (const double m : problem.model().particles.mass) // rank 0 holds the particles
    particles += m;
  const auto& lumped = problem.continuum().lumped_mass();
  double continuum = 0;
  for (const auto i : lumped.locally_owned_elements())
    continuum += lumped(i);
  return dealii::Utilities::MPI::sum(particles + continuum / 3, comm);
}

// The band's mass partition: a band particle takes the share of its mass its FE nodes lack
// (blending.h), so particles and continuum together weigh what the body weighs, rho V (the
// lattice's spheres carry rho d^3 each). Exact (1e-9; measured 1e-14) where the band is one
// plane's: the bar of the wave checks (h = d) and a slab of particles across a cube, coupled on
// its two faces. Where the bands of two faces meet (a block coupled on all six faces) the
// weight has a kink along the edges' diagonals that neither the FE quadrature nor the nodal
// ratio follows: there the sum is 2.3e-3 of the body's mass light (0.12 % of the band's), held
// below 5e-3. A continuum whose lumped mass is left unweighted in the band counts the band's
// mass twice: +0.22 % in the bar, +3.8 % in the slab, +1.8 % in the block.
void check_band_mass(MPI_Comm comm)
{
  auto report = [](const char* what, double mass, double body, double limit)
  {
    std::printf("%s: particles + continuum %.12e kg, rho V %.12e kg (rel. %.1e)\n", what, mass,
                body, mass / body - 1);
    char text[160];
    std::snprintf(text, sizeof text, "%s: blended masses sum to rho V within %.0e", what, limit);
    check(std::abs(mass / body - 1) < limit, text);
  };
  {
    const Bar bar;
    auto problem = bar.make(comm);
    report("bar (the wave checks)", blended_mass(*problem, comm),
           bar.density * (bar.fe_length + bar.particle_length) * std::pow(bar.width(), 2), 1e-9);
  }
  for (const bool slab : {true, false})
  {
    Block block;
    block.slab = slab;
    auto problem = block.make(comm);
    report(slab ? "slab across a cube (two coupled faces)" : "block in a cube (six coupled faces)",
           blended_mass(*problem, comm),
           block.density * std::pow(block.domain * block.spacing(), 3), slab ? 1e-9 : 5e-3);
  }
}

/// Largest forces after one step from a given state, over the scale of the forces a strain of
/// 1e-4 puts on a bond (k_n 1e-4 d): bonds, net particle forces, FE internal forces, ties.
struct Forces
{
  double bonds = 0, particles = 0, fe = 0, ties = 0;
  double largest() const { return std::max({bonds, particles, fe, ties}); }
};

Forces forces_after_one_step(coupling::CoupledProblem& problem, const double scale)
{
  problem.step(true);
  Forces f;
  const auto& b = problem.model().bonds;
  for (std::size_t k = 0; k < b.size(); ++k)
    f.bonds = std::max(f.bonds, std::max(b.force[k].norm(), b.moment[k].norm() / 0.005));
  const auto& p = problem.model().particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    f.particles = std::max(f.particles, p.force[i].norm());
  f.fe = problem.continuum().internal_forces().linfty_norm();
  for (const double q : problem.tie_forces())
    f.ties = std::max(f.ties, std::abs(q));
  f.bonds /= scale, f.particles /= scale, f.fe /= scale, f.ties /= scale;
  return f;
}

void patch_rigid(const Block& block, MPI_Comm comm)
{
  const double scale = Bar().bond().kn * 1e-4 * block.spacing();
  {
    auto problem = block.make(comm);
    const Vec3 t(1e-3, -2e-3, 0.5e-3);
    problem->set_initial_state([&](const Vec3&) { return t; },
                               [](const Vec3&) { return Vec3::Zero(); });
    const auto f = forces_after_one_step(*problem, scale);
    std::printf("rigid translation (1e-3 m): bonds %.2e, particles %.2e, FE %.2e, ties %.2e "
                "(of k_n 1e-4 d)\n",
                f.bonds, f.particles, f.fe, f.ties);
    check(f.largest() < 1e-9, "rigid translation: every force below 1e-9 of the load scale");
  }
  {
    auto problem = block.make(comm);
    const double angle = 1e-6;
    const Vec3 axis = Vec3(1, 2, 3).normalized(), centre = Vec3::Constant(8 * block.spacing());
    const dem::Quat q(Eigen::AngleAxisd(angle, axis));
    // FE: the linear rotation field, strain-free; particles: the exact rotation, orientations too
    problem->set_initial_state([&](const Vec3& X) { return Vec3(angle * axis.cross(X - centre)); },
                               [](const Vec3&) { return Vec3::Zero(); });
    auto& p = problem->model().particles;
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      p.position[i] = centre + q * (p.reference_position[i] - centre);
      p.orientation[i] = q;
    }
    const auto f = forces_after_one_step(*problem, scale);
    std::printf("rigid rotation (1e-6 rad): bonds %.2e, particles %.2e, FE %.2e, ties %.2e "
                "(of k_n 1e-4 d)\n",
                f.bonds, f.particles, f.fe, f.ties);
    check(f.largest() < 1e-9, "rigid rotation: every force below 1e-9 of the load scale");
  }
}

void check_patch_rigid(MPI_Comm comm)
{
  patch_rigid(Block(), comm);
}

/// The same with a ball of particles (a gmsh volume): the band cuts the FE cells.
void check_patch_rigid_volume(MPI_Comm comm)
{
  Block block;
  block.region_file = mesh_dir + "/region_sphere.msh";
  block.domain = 24;
  auto problem = block.make(comm);
  std::printf("ball of radius 10 d: %zu particles, %zu in the band\n", problem->n_particles(),
              problem->n_interface_particles());
  patch_rigid(block, comm);
}

/// Uniform strain on the outer FE faces; the particle-only region's strain after relaxation.
double uniform_strain(const Block& block, MPI_Comm comm, Forces& ghost)
{
  Eigen::Matrix3d eps;
  eps << 1.0e-4, 0.3e-4, -0.2e-4, 0.3e-4, -0.5e-4, 0.4e-4, -0.2e-4, 0.4e-4, 0.8e-4;
  const auto u = [&](const Vec3& X) { return Vec3(eps * X); };
  std::vector<coupling::DrivenBoundary> driven;
  for (const char* face : {"x-min", "x-max", "y-min", "y-max", "z-min", "z-max"})
    driven.push_back({face, {{true, true, true}}, u, [](double) { return 1.0; }});
  Block damped = block;
  // about critical damping of the block's lowest mode (omega ~ pi c / L)
  const double c = Bar().wave_speed();
  damped.mass_damping = 2 * 3.14159 * c / (16 * block.spacing());
  auto problem = damped.make(comm, driven);
  problem->set_initial_state(u, [](const Vec3&) { return Vec3::Zero(); });
  const double scale = Bar().bond().kn * 1e-4 * block.spacing();
  ghost = forces_after_one_step(*problem, scale);
  ghost.bonds = 0; // bonds carry the strain; the ghost forces are the net ones
  ghost.fe = 0;
  // relax: until the kinetic energy is 1e-14 of the strain energy
  for (long n = 1; n < 20000; ++n)
  {
    const bool record = n % 100 == 0;
    problem->step(record);
    if (record)
    {
      const auto& e = problem->energies();
      if (e.dem_kinetic + e.fe_kinetic < 1e-14 * (e.dem_strain + e.fe_strain))
        break;
    }
  }
  const auto& h = problem->handshake();
  const auto fit = coupling::fit_particle_strain(problem->model().particles, [&](const Vec3& X)
                                                 { return h.in_particle_only(X); });
  double err = 0;
  for (int r = 0; r < 3; ++r)
    for (int c2 = 0; c2 < 3; ++c2)
      err = std::max(err, std::abs(fit[3 * r + c2] - eps(r, c2)));
  return err / eps.cwiseAbs().maxCoeff();
}

void check_patch_strain(MPI_Comm comm)
{
  for (const double h : {1.0, 2.0})
  {
    Block block;
    block.element_size = h * block.spacing();
    Forces ghost;
    const double error = uniform_strain(block, comm, ghost);
    std::printf("uniform strain, h = %g d: ghost forces at the exact state: particles %.2e, "
                "ties %.2e (of k_n 1e-4 d); particle-only strain error %.2e of the largest "
                "component\n",
                h, ghost.particles, ghost.ties, error);
    check(error < 0.01, "uniform strain reproduced in the particle region within 1 %");
  }
}

void check_patch_strain_volume(MPI_Comm comm)
{
  // A curved band cuts the lattice in a staircase, so a box face's exact cancellation is not
  // available (coupled_case.cc): the error falls with d / R and d / L (measured, h = d: R = 6 d,
  // L = 2 d 2.4 %, L = 3 d 2.1 %, L = 4 d 1.3 %; R = 10 d, L = 2 d 1.2 %, L = 3 d 0.83 %).
  Block block;
  block.region_file = mesh_dir + "/region_sphere.msh";
  block.domain = 24;
  block.band_width = 3 * block.spacing();
  Forces ghost;
  const double error = uniform_strain(block, comm, ghost);
  std::printf("uniform strain, ball of radius 10 d, band 3 d, h = d: ghost forces at the exact "
              "state: particles %.2e, ties %.2e (of k_n 1e-4 d); particle-only strain error "
              "%.2e of the largest component\n",
              ghost.particles, ghost.ties, error);
  check(error < 0.01, "uniform strain reproduced in the ball's particle-only region within 1 %");
}

/// The region of a gmsh volume: the ball's volume, containment and surface distance against the
/// sphere (within its facets' sag); a box-shaped volume gives the
/// box's weights.
void check_region_volume(MPI_Comm)
{
  using coupling::Handshake;
  const double R = 0.1;
  const Vec3 centre = Vec3::Constant(0.12);
  const auto ball = coupling::read_region_volume(mesh_dir + "/region_sphere.msh", "region");
  const double exact = 4.0 / 3.0 * std::numbers::pi * R * R * R;
  std::printf("ball: %zu tetrahedra, %zu boundary triangles, volume %.6e m^3 (sphere %.6e, "
              "%.3f %%)\n",
              ball.n_tetrahedra(), ball.boundary().size(), ball.volume(), exact,
              100 * (ball.volume() / exact - 1));
  check(std::abs(ball.volume() / exact - 1) < 3e-3,
        "volume of the ball within 0.3 % of 4/3 pi R^3");
  bool inside = true, outside = true;
  double distance_error = 0;
  const coupling::SurfaceDistance surface(ball.boundary(), 2 * R);
  for (int k = 0; k < 200; ++k)
  {
    const Vec3 e =
        Vec3(std::sin(1.3 * k + 0.2), std::cos(0.7 * k), std::sin(2.9 * k + 1)).normalized();
    inside = inside && ball.contains(centre + 0.99 * R * e) && ball.contains(centre + 0.3 * R * e);
    outside = outside && !ball.contains(centre + 1.01 * R * e);
    const Vec3 x = centre + (0.2 + 0.7 * std::abs(std::sin(5.1 * k))) * R * e;
    distance_error =
        std::max(distance_error, std::abs(surface.distance(x) - (R - (x - centre).norm())));
  }
  // A facet inscribed in the sphere departs from it by at most R - sqrt(R^2 - rc^2), rc its
  // circumradius: the bound for the distance error.
  double sag = 0;
  for (const auto& t : ball.boundary())
  {
    const double a = (t[1] - t[0]).norm(), b = (t[2] - t[1]).norm(), c = (t[0] - t[2]).norm();
    const double rc = a * b * c / (2 * (t[1] - t[0]).cross(t[2] - t[0]).norm());
    sag = std::max(sag, R - std::sqrt(std::max(0.0, R * R - rc * rc)));
  }
  std::printf("ball: largest surface distance error %.3e m (largest facet sag %.3e m)\n",
              distance_error, sag);
  check(inside && outside, "points at 0.3 R and 0.99 R inside the ball, at 1.01 R outside");
  check(distance_error <= sag, "distance to the surface within the largest facet's sag");

  // The compression specimen's particle region as a box and as a volume of tetrahedra.
  coupling::HandshakeGeometry box;
  box.domain_lo = Vec3::Zero();
  box.domain_hi = Vec3(0.25, 0.1, 0.1);
  box.particle_lo = Vec3(0.08, 0, 0);
  box.particle_hi = Vec3(0.17, 0.1, 0.1);
  box.band_width = 0.03;
  box.particle_radius = 0.005;
  coupling::HandshakeGeometry volume = box;
  volume.region = std::make_shared<const coupling::RegionVolume>(
      coupling::read_region_volume(mesh_dir + "/region_compression_box.msh", "region"));
  const Handshake a(box), b(volume);
  double weight_difference = 0;
  int disagree = 0;
  for (int k = 0; k < 20000; ++k)
  {
    const Vec3 x(0.25 * (0.5 + 0.5 * std::sin(0.37 * k)),
                 0.1 * (0.5 + 0.5 * std::sin(1.91 * k + 1)),
                 0.1 * (0.5 + 0.5 * std::sin(2.53 * k + 2)));
    weight_difference = std::max({weight_difference, std::abs(a.alpha(x) - b.alpha(x)),
                                  std::abs(a.particle_mass_share(x) - b.particle_mass_share(x))});
    disagree += a.in_band(x) != b.in_band(x) || a.in_particle_only(x) != b.in_particle_only(x);
  }
  std::printf("box as a volume: largest weight difference %.2e, %d of 20000 points classified "
              "differently\n",
              weight_difference, disagree);
  check(weight_difference < 1e-12 && disagree == 0,
        "a box-shaped volume gives the box's weights and zones (1e-12)");
}

// Exploration (not a ctest): coupling_check wave_point LAMBDA/d H/d TYING SOLVE FLOOR [FS]
void wave_point(MPI_Comm comm, char** argv)
{
  Bar bar;
  const double lambda = std::atof(argv[2]) * bar.spacing();
  bar.element_size = std::atof(argv[3]) * bar.spacing();
  bar.tying = std::string(argv[4]) == "node" ? coupling::Tying::node : coupling::Tying::particle;
  bar.solve = std::string(argv[5]) == "lumped" ? coupling::ConstraintSolve::lumped
                                               : coupling::ConstraintSolve::exact;
  bar.weight_floor = std::atof(argv[6]);
  bar.fine_scale_damping = argv[7] ? std::atof(argv[7]) : 0.0;
  bar.fe_length = std::max(0.8, 8 * lambda);
  bar.particle_length = std::max(0.8, 8 * lambda);
  bar.band_width = std::max(3 * bar.spacing(), 2 * bar.element_size);
  for (const bool from_continuum : {true, false})
  {
    const auto r = wave_through_band(bar, lambda, from_continuum, comm);
    std::printf("%s R %.4e T %.6f balance %.3e\n", from_continuum ? "in " : "out", r.reflected,
                r.transmitted, r.balance);
  }
}
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 2)
  {
    std::cerr << "usage: coupling_check wave|...\n";
    return 2;
  }
  const std::string what = argv[1];
  if (what == "wave_point" && argc >= 7)
  {
    wave_point(MPI_COMM_WORLD, argv);
    return 0;
  }
  const std::map<std::string, std::function<void(MPI_Comm)>> checks = {
      {"wave", check_wave},
      {"band_mass", check_band_mass},
      {"patch_rigid", check_patch_rigid},
      {"patch_strain", check_patch_strain},
      {"patch_rigid_volume", check_patch_rigid_volume},
      {"patch_strain_volume", check_patch_strain_volume},
      {"region_volume", check_region_volume}};
  if (argc >= 3)
    mesh_dir = argv[2];
  try
  {
    const auto it = checks.find(what);
    if (it == checks.end())
    {
      std::cerr << "coupling_check: unknown check '" << what << "'\n";
      return 2;
    }
    it->second(MPI_COMM_WORLD);
  }
  catch (const std::exception& e)
  {
    std::cerr << "coupling_check: error: " << e.what() << '\n';
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
