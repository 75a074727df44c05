// Checks of the adaptive particle region (coupling/adaptive_region.h, packing_strength.h,
// region_growth.cc): one check per ctest, chosen by the first argument. Each prints its numbers
// and the reference with the tolerance, and exits 1 if a check fails.
//   utilisation_closed_form  the simple cubic lattice's strength in tension and shear
//   region_cells             a union of cells as a region volume: volume, containment, depth
//   growth_uniform_strain    a growth event in a uniformly strained block: the energy jump, the
//                            new particles carrying the strain, no shock
//   growth_refines_grid      the same where the growth refines the continuum's coarse grid
#include "coupling/adaptive_region.h"
#include "coupling/continuum_tensor.h"
#include "coupling/coupled_problem.h"
#include "coupling/measurements.h"
#include "dem/bonds/bond_model.h"
#include "dem/measurements/particle_stress.h"

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

void check(const bool ok, const std::string& what)
{
  std::printf("%s: %s\n", ok ? "PASS" : "FAIL", what.c_str());
  failures += !ok;
}

const double radius = 0.005, spacing = 2 * radius;

dem::BondMaterial material()
{
  dem::BondMaterial m;
  m.model = dem::BondModel::parallel_bond;
  m.youngs_modulus = 4e9;
  m.poisson_ratio = 0.3;
  m.stiffness_ratio = 4.2;
  return m;
}

coupling::PackingStrength cubic_strength(double tensile, double shear)
{
  coupling::PackingStrength s;
  const std::vector<Vec3> axes = {Vec3::UnitX(), -Vec3::UnitY(), Vec3::UnitZ(), Vec3::UnitX()};
  s.families =
      coupling::bond_families(axes, std::vector<double>(4, spacing), std::vector<double>(4, radius),
                              std::vector<double>(4, radius), material());
  s.law.mode = dem::FailureMode::brittle;
  s.tensile_strength = tensile;
  s.shear_strength = shear;
  return s;
}

/// The simple cubic lattice (C11 = k_n / d, C44 = k_s / (2 d)) fails in uniaxial tension at
/// sigma_xx = sigma_t pi R_b^2 / d^2 and in pure shear at sigma_xy = tau_c pi R_b^2 / d^2
/// (packing_strength.h): U = 1 there, for any axis.
void check_utilisation_closed_form(MPI_Comm)
{
  const double sigma_t = 1e6, tau_c = 2e6;
  const auto s = cubic_strength(sigma_t, tau_c);
  check(s.families.size() == 3, "three bond directions of the cubic lattice (duplicates and "
                                "signs merged)");
  const auto k = dem::bond_stiffness(material(), spacing, radius, radius);
  const double C11 = k.kn / spacing, C44 = k.ks / (2 * spacing);
  const double area_ratio = std::numbers::pi * radius * radius / (spacing * spacing);
  double worst = 0;
  for (int a = 0; a < 3; ++a)
  {
    Eigen::Matrix3d eps = Eigen::Matrix3d::Zero();
    eps(a, a) = sigma_t * area_ratio / C11; // sigma_aa = C11 eps_aa
    const double U = coupling::utilisation(s, eps);
    worst = std::max(worst, std::abs(U - 1));
    Eigen::Matrix3d shear = Eigen::Matrix3d::Zero();
    const int b = (a + 1) % 3;
    shear(a, b) = shear(b, a) = tau_c * area_ratio / (2 * C44); // sigma_ab = 2 C44 eps_ab
    const double Us = coupling::utilisation(s, shear);
    worst = std::max(worst, std::abs(Us - 1));
    std::printf("axis %c: tension U = %.15f, shear %c%c U = %.15f\n", "xyz"[a], U, "xyz"[a],
                "xyz"[b], Us);
  }
  check(worst < 1e-12, "U = 1 at the closed-form tensile and shear strengths (within 1e-12)");
  Eigen::Matrix3d squeeze = Eigen::Matrix3d::Zero();
  squeeze(2, 2) = -1e-3;
  check(coupling::utilisation(s, squeeze) == 0, "compression alone does not load the bonds "
                                                "(constant shear strength)");
}

/// A union of cells as a region: the L-shaped union of two boxes of cells, its volume, what it
/// contains, and the depth below its faces inside the domain.
void check_region_cells(MPI_Comm)
{
  coupling::HandshakeGeometry g;
  g.domain_lo = Vec3::Zero();
  g.domain_hi = Vec3(20, 10, 10) * spacing;
  g.band_width = 3 * spacing;
  g.particle_radius = radius;
  coupling::GridLines lines;
  for (int d = 0; d < 3; ++d)
    for (int i = 0; i <= int(std::lround(g.domain_hi[d] / spacing)); ++i)
      lines[d].push_back(i * spacing);
  coupling::AdaptiveRegionSettings settings;
  coupling::AdaptiveRegion region(settings, lines, g, cubic_strength(1e6, 2e6), {}, spacing);
  // cells 0 <= i < 8 (all j, k < 4) and 0 <= i < 4 (all j, 4 <= k < 8)
  std::vector<char> cells(region.n_cells(), 0);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < (k < 4 ? 8 : 4); ++i)
        cells[(std::size_t(k) * 10 + j) * 20 + i] = 1;
  region.set_cells(cells);
  const auto volume = region.volume();
  const double expected = (8 * 10 * 4 + 4 * 10 * 4) * std::pow(spacing, 3);
  std::printf("L-shaped union of %zu cells: volume %.6e m^3 (expected %.6e)\n",
              region.n_region_cells(), volume->volume(), expected);
  check(std::abs(volume->volume() - expected) < 1e-12 * expected, "volume of the union");
  g.region = volume;
  const coupling::Handshake h(g);
  const double d = spacing;
  // inside the lower box, 1.5 d below its top face (z = 4 d, open for 4 d < x < 8 d), 2 d from
  // its face x = 8 d
  const Vec3 a(6 * d, 5 * d, 2.5 * d);
  // inside the upper box, 1.5 d from its face x = 4 d, 2.5 d below its top (z = 8 d)
  const Vec3 b(2.5 * d, 5 * d, 5.5 * d);
  // inside the lower box, 0.5 d from its face x = 8 d (its bottom z = 0 lies on the domain)
  const Vec3 c(7.5 * d, 5 * d, 0.5 * d);
  std::printf("depths: %.4f d, %.4f d, %.4f d (expected 1.5, 1.5, 0.5)\n", h.depth(a) / d,
              h.depth(b) / d, h.depth(c) / d);
  check(std::abs(h.depth(a) - 1.5 * d) < 1e-9 && std::abs(h.depth(b) - 1.5 * d) < 1e-9 &&
            std::abs(h.depth(c) - 0.5 * d) < 1e-9,
        "depth below the faces inside the domain (faces on the domain's faces are not coupled)");
  check(h.in_particle_box(a) && h.in_particle_box(b) &&
            !h.in_particle_box(Vec3(6 * d, 5 * d, 6 * d)),
        "containment of the union (the re-entrant corner is outside)");
}

/// A block of the simple cubic lattice's continuum, 16 d on a side, strained uniformly through
/// its driven faces; particles in the middle cube of 8 d (band 3 d); the region then grows by a
/// layer of cells on every side. The new particles come from the continuum at X + u(X) and are
/// bonded in the reference configuration, so the stored energy must not jump (goal 1 % of the
/// strain energy), the particles added must carry the energy the continuum gave up, and the
/// particle-only region must go on carrying the strain.
/// A block of n^3 cells of the lattice's spacing, particles in the cells [box_lo, box_hi)^3,
/// grown to [grown_lo, grown_hi)^3; the FE grid's coarsening and fine margin (adaptive_region.h).
struct GrowthCase
{
  int n = 16, box_lo = 4, box_hi = 12, grown_lo = 3, grown_hi = 13;
  int coarsening = 4, margin = 0;
  long relax_steps = 4000;
};

void growth_uniform_strain(MPI_Comm comm, const GrowthCase& gc)
{
  const double d = spacing;
  const double density = 2500;
  dem::CaseConfig c;
  c.particles.kind = dem::ParticleSource::Kind::cubic;
  c.particles.radius = radius;
  c.particles.density = density;
  c.particles.scale_density_by_porosity = true;
  c.particles.origin = Vec3::Constant(gc.box_lo * d);
  c.particles.box_size = Vec3::Constant((gc.box_hi - gc.box_lo) * d);
  c.bonds.material = material();
  c.damage.law.mode = dem::FailureMode::brittle;
  c.damage.tensile_strength = 1e12; // nothing breaks: the utilisation needs strengths
  c.damage.shear_strength = 1e12;
  c.run.threads = 1;
  fem::Parameters fe;
  fe.density = density;
  coupling::CouplingSettings s;
  s.geometry.domain_lo = Vec3::Zero();
  s.geometry.domain_hi = Vec3::Constant(gc.n * d);
  s.geometry.particle_lo = c.particles.origin;
  s.geometry.particle_hi = c.particles.origin + c.particles.box_size;
  s.geometry.band_width = 3 * d;
  s.geometry.particle_radius = radius;
  s.element_size = Vec3::Constant(d);
  s.band_element_size = d;
  const auto k = dem::bond_stiffness(material(), d, radius, radius);
  s.tensor = coupling::simple_cubic_tensor(k.kn, k.ks, d);
  s.mass_damping = 2 * 3.14159 * std::sqrt(k.kn / d / density) / (16 * d); // ~ critical
  s.adaptive.enabled = true;
  s.adaptive.envelope_coarsening = gc.coarsening;
  s.adaptive.fine_margin = gc.margin;
  Eigen::Matrix3d eps;
  eps << 1.0e-4, 0.3e-4, -0.2e-4, 0.3e-4, -0.5e-4, 0.4e-4, -0.2e-4, 0.4e-4, 0.8e-4;
  const auto u = [&](const Vec3& X) { return Vec3(eps * X); };
  for (const char* face : {"x-min", "x-max", "y-min", "y-max", "z-min", "z-max"})
    s.driven.push_back({face, {{true, true, true}}, u, [](double) { return 1.0; }});
  coupling::CoupledProblem problem(s, fe, c, comm);
  problem.setup();
  problem.set_initial_state(u, [](const Vec3&) { return Vec3::Zero(); });
  problem.step(true);
  const auto& region = *problem.adaptive_region();
  const std::size_t n0 = problem.n_particles();
  std::vector<char> cells = region.cells();
  const int n = gc.n;
  auto grown = [&](int i) { return i >= gc.grown_lo && i < gc.grown_hi; };
  for (int kk = 0; kk < n; ++kk)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (grown(i) && grown(j) && grown(kk))
          cells[(std::size_t(kk) * n + j) * n + i] = 1;
  const auto dofs_before = problem.continuum().get_dof_handler().n_dofs();
  const double dem_strain_before = problem.energies().dem_strain;
  // the two sides' strain energies of the same state, before and after the growth
  auto strain_now = [&]
  {
    return std::pair(
        dem::particle_stresses(problem.model().particles, problem.model().bonds).strain_energy,
        problem.continuum().energies_now().strain);
  };
  const auto [dem0, fe0] = strain_now();
  const auto e = problem.grow_region(cells);
  const auto [dem1, fe1] = strain_now();
  const auto dofs_after = problem.continuum().get_dof_handler().n_dofs();
  std::printf("continuum: %u DoFs before the growth, %u after\n", unsigned(dofs_before),
              unsigned(dofs_after));
  if (gc.margin > 0) // the grown region's fine zone reaches past the coarse lines
    check(dofs_after > dofs_before, "the growth refined the continuum's grid");
  std::printf("the particles' strain energy grew by %.6e J, the continuum's fell by %.6e J "
              "(%.2e apart, relative)\n",
              dem1 - dem0, fe0 - fe1, std::abs((dem1 - dem0) - (fe0 - fe1)) / (dem1 - dem0));
  check(std::abs((dem1 - dem0) - (fe0 - fe1)) < 0.01 * (dem1 - dem0),
        "the particles added carry the strain energy the continuum gave up, within 1 %");
  std::printf("growth: +%zu particles (%zu -> %zu), +%zu bonds, +%zu cells; stored energy "
              "%.9e J -> %.9e J, jump %.3e J = %.2e of the strain energy %.6e J\n",
              e.particles_added, n0, e.n_particles, e.bonds_added, e.cells_added, e.energy_before,
              e.energy_after, e.energy_jump(), e.energy_jump_ratio(), e.strain_energy);
  const auto cube = [](int a) { return std::size_t(a) * a * a; };
  const std::size_t joined = cube(gc.grown_hi - gc.grown_lo) - cube(gc.box_hi - gc.box_lo);
  check(e.particles_added == joined, "the particles of the added layers joined");
  check(e.energy_jump_ratio() < 0.01, "the energy jump within 1 % of the strain energy");
  // relax: the particle-only region carries the strain, nothing rings
  double largest_kinetic = 0;
  for (long step = 1; step <= gc.relax_steps; ++step)
  {
    const bool record = step % 50 == 0;
    problem.step(record);
    if (!record)
      continue;
    const auto& en = problem.energies();
    largest_kinetic = std::max(largest_kinetic,
                               (en.dem_kinetic + en.fe_kinetic) / (en.dem_strain + en.fe_strain));
  }
  const auto& en = problem.energies();
  std::printf("after %ld steps: particles' strain energy %.6e J (%.6e J before the growth), "
              "continuum %.6e J; largest kinetic share %.2e; balance error %.2e\n",
              gc.relax_steps, en.dem_strain, dem_strain_before, en.fe_strain, largest_kinetic,
              en.balance_error());
  const auto& h = problem.handshake();
  const auto fit = coupling::fit_particle_strain(problem.model().particles, [&](const Vec3& X)
                                                 { return h.in_particle_only(X); });
  double err = 0;
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q)
      err = std::max(err, std::abs(fit[3 * r + q] - eps(r, q)));
  err /= eps.cwiseAbs().maxCoeff();
  std::printf("particle-only strain error %.2e of the largest component\n", err);
  check(err < 0.01, "the grown particle-only region carries the strain within 1 %");
  check(largest_kinetic < 1e-3, "no shock: the kinetic energy stays below 1e-3 of the strain "
                                "energy after the growth");
}

void check_growth_uniform_strain(MPI_Comm comm)
{
  growth_uniform_strain(comm, GrowthCase{});
}

/// The growth refines the continuum's grid: a 24-cell block, every 4th line away from the region
/// (k = 4), 3 cells fine beyond its faces; the region grows by 3 layers, so that its fine zone
/// takes in the coarse cells at the block's faces (new nodes at 1/4, 1/2, 3/4 of them).
void check_growth_refines_grid(MPI_Comm comm)
{
  growth_uniform_strain(comm, GrowthCase{24, 8, 16, 5, 19, 4, 3, 2000});
}
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 2)
  {
    std::cerr << "usage: adaptive_check utilisation_closed_form|region_cells|"
                 "growth_uniform_strain|growth_refines_grid\n";
    return 2;
  }
  const std::map<std::string, std::function<void(MPI_Comm)>> checks = {
      {"utilisation_closed_form", check_utilisation_closed_form},
      {"region_cells", check_region_cells},
      {"growth_uniform_strain", check_growth_uniform_strain},
      {"growth_refines_grid", check_growth_refines_grid}};
  try
  {
    const auto it = checks.find(argv[1]);
    if (it == checks.end())
    {
      std::cerr << "adaptive_check: unknown check '" << argv[1] << "'\n";
      return 2;
    }
    it->second(MPI_COMM_WORLD);
  }
  catch (const std::exception& e)
  {
    std::cerr << "adaptive_check: error: " << e.what() << '\n';
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
