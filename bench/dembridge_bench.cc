// dembridge-bench: throughput of the explicit DEM core on a bonded HCP lattice.
// The lattice fills the thesis' 0.25 x 0.1 x 0.1 m specimen with r = 2.5 mm spheres (about
// 25,000 particles and 140,000 bonds, every touching pair bonded with the TBBM); seeded random
// velocities keep the bonds deforming. Prints one JSON object (and writes it with --json).
#include "dem/bonds/bonding.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/packing/packings.h"
#include "dem/solvers/time_step.h"
#include <CLI/CLI.hpp>
#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <time.h>

using namespace dembridge::dem;

namespace
{
/// CPU time of the whole process (all threads), s: on a machine shared with other jobs the
/// single-thread figure per CPU-second is the reproducible one.
double process_cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
} // namespace

int main(int argc, char** argv)
{
  CLI::App app{"dembridge-bench: bond-updates per second of the DEM core"};
  int threads = 1, steps = 300;
  double radius = 2.5e-3, damping = 0.05;
  std::string model_name = "timoshenko", json_file;
  app.add_option("--threads", threads, "Threads")->check(CLI::Range(1, 256));
  app.add_option("--steps", steps, "Time steps to time")->check(CLI::Range(1, 100000000));
  app.add_option("--radius", radius, "Particle radius (m)")->check(CLI::PositiveNumber);
  app.add_option("--model", model_name, "Bond model")
      ->check(CLI::IsMember({"parallel_bond", "euler_bernoulli", "timoshenko"}));
  app.add_option("--damping", damping, "Bond dashpot damping ratio (0: no dashpots)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--json", json_file, "Also write the result to this file");
  CLI11_PARSE(app, argc, argv);

  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  ParticleSource src;
  src.kind = ParticleSource::Kind::hcp;
  src.radius = radius;
  src.box_size = Vec3(0.25, 0.1, 0.1);
  ParticleStore p;
  generate_particles(src, p);
  BondMaterial mat;
  mat.model = bond_model_from_name(model_name);
  mat.youngs_modulus = 4e9;
  mat.poisson_ratio = 0.3;
  BondStore b;
  form_bonds(p, b, mat, 1.0);
  assign_bond_damping(p, b, damping);
  std::mt19937 rng(12345);
  std::normal_distribution<double> n01(0, 1);
  for (std::size_t i = 0; i < p.size(); ++i)
    p.velocity[i] = 1e-3 * Vec3(n01(rng), n01(rng), n01(rng));
  const double dt = 0.8 * estimate_critical_time_step(p, b).critical();
  ExplicitSolver solver(p, b, {}, {}, {}, {dt, 0.0, threads});
  const double setup = std::chrono::duration<double>(clock::now() - t0).count();

  for (int s = 0; s < 10; ++s) // warm-up: page in, settle thread pools
    solver.step(false);
  const double c1 = process_cpu_seconds();
  const auto t1 = clock::now();
  for (int s = 0; s < steps; ++s)
    solver.step(false);
  const double wall = std::chrono::duration<double>(clock::now() - t1).count();
  const double cpu = process_cpu_seconds() - c1;
  solver.step(true);

  nlohmann::json j;
  j["benchmark"] = "hcp_lattice_explicit";
  j["bond_model"] = model_name;
  j["bond_damping_ratio"] = damping;
  j["n_particles"] = p.size();
  j["n_bonds"] = b.size();
  j["threads"] = threads;
  j["steps"] = steps;
  j["wall_seconds"] = wall;
  j["cpu_seconds"] = cpu;
  j["bond_updates_per_cpu_second"] = double(b.size()) * steps / cpu;
  j["setup_seconds"] = setup;
  j["bond_updates_per_second"] = double(b.size()) * steps / wall;
  j["particle_steps_per_second"] = double(p.size()) * steps / wall;
  j["energy_balance_error"] = solver.energy().relative_error();
  std::cout << j.dump() << std::endl;
  if (!json_file.empty())
    std::ofstream(json_file) << j.dump(2) << '\n';
  return 0;
}
