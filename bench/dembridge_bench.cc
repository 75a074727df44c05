// dembridge-bench: throughput of the explicit DEM core beside the machine's reference loop.
// The specimen fills the thesis' 0.25 x 0.1 x 0.1 m box with spheres of radius r (2.5 mm: 26,004
// particles and 147,618 TBBM bonds on the HCP lattice), every touching pair bonded; the
// particles are renumbered along a space-filling curve as every case is (renumbering.h), seeded
// random velocities keep the bonds deforming. For each thread count the full model
// (ExplicitSolver: unified law in total co-rotational form, dashpots, exact energy booking) and
// the plain parallel-bond loop (plain_bond_loop.h) run in the same process on copies of the
// same specimen, alternating in rounds so that both see the same machine. Prints one JSON object
// (and writes it with --json).
#include "dem/bonds/bonding.h"
#include "dem/model/renumbering.h"
#include "dem/packing/packings.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/time_step.h"
#include "plain_bond_loop.h"
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <sys/resource.h>
#include <thread>
#include <time.h>

using namespace dembridge::dem;
using dembridge::bench::PlainBondLoop;

namespace
{
/// CPU time of the whole process (all threads), s: on a machine shared with other jobs the
/// figure per CPU-second is the more reproducible one.
double process_cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Timing
{
  double wall, cpu;
};

template <class Step> Timing time_steps(Step&& step, int steps)
{
  using clock = std::chrono::steady_clock;
  const double c0 = process_cpu_seconds();
  const auto t0 = clock::now();
  for (int s = 0; s < steps; ++s)
    step();
  return {std::chrono::duration<double>(clock::now() - t0).count(), process_cpu_seconds() - c0};
}

/// Rates of one loop over the rounds: best and median bond-updates per second (wall) and per
/// CPU-second.
nlohmann::json rates(const std::vector<Timing>& rounds, double bonds, double particles, int steps)
{
  std::vector<double> wall, cpu;
  for (const auto& t : rounds)
    wall.push_back(bonds * steps / t.wall), cpu.push_back(bonds * steps / t.cpu);
  nlohmann::json j;
  j["bond_updates_per_second"] = *std::max_element(wall.begin(), wall.end());
  j["bond_updates_per_second_median"] = median(wall);
  j["bond_updates_per_second_rounds"] = wall;
  j["bond_updates_per_cpu_second"] = *std::max_element(cpu.begin(), cpu.end());
  j["particle_steps_per_second"] = *std::max_element(wall.begin(), wall.end()) * particles / bonds;
  return j;
}
} // namespace

int main(int argc, char** argv)
{
  CLI::App app{"dembridge-bench: bond-updates per second of the DEM core and of the plain loop"};
  std::vector<int> thread_counts{1};
  int steps = 100, rounds = 5;
  double radius = 2.5e-3, damping = 0.05, multiplier = 0;
  std::string model_name = "timoshenko", packing = "hcp", json_file, particle_file;
  bool plain = true, renumber = true;
  app.add_option("--threads", thread_counts, "Thread counts (e.g. --threads 1 2)")
      ->check(CLI::Range(1, 256));
  app.add_option("--steps", steps, "Time steps per round")->check(CLI::Range(1, 100000000));
  app.add_option("--rounds", rounds, "Rounds (full model and plain loop alternate)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--radius", radius, "Particle radius (m)")->check(CLI::PositiveNumber);
  app.add_option("--packing", packing, "hcp | random (seed 1, target porosity 0.37)")
      ->check(CLI::IsMember({"hcp", "random"}));
  app.add_option("--particles-file", particle_file,
                 "CSV x,y,z,r: read the particles from it when it exists, else write them there");
  app.add_option("--multiplier", multiplier,
                 "Contact radius multiplier of bond formation (default 1 for hcp, 1.04 for "
                 "random, as examples/compression_random.prm)")
      ->check(CLI::PositiveNumber);
  app.add_option("--model", model_name, "Bond model")
      ->check(CLI::IsMember({"parallel_bond", "euler_bernoulli", "timoshenko"}));
  app.add_option("--damping", damping, "Bond dashpot damping ratio (0: no dashpots)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_flag("!--no-plain", plain, "Leave out the plain reference loop");
  app.add_flag("!--no-renumber", renumber, "Keep the packing's own particle order");
  app.add_option("--json", json_file, "Also write the result to this file");
  CLI11_PARSE(app, argc, argv);

  double load_average = -1; // other work on the machine (the VM is shared)
  std::ifstream("/proc/loadavg") >> load_average;
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  ParticleSource src;
  src.kind = packing == "hcp" ? ParticleSource::Kind::hcp : ParticleSource::Kind::random;
  src.radius = radius;
  src.box_size = Vec3(0.25, 0.1, 0.1);
  // why: the recorded figures (README, RESULTS.md) rest on the measured estimate's packing
  src.predict_jamming = false;
  ParticleStore p;
  if (!particle_file.empty() && std::ifstream(particle_file).good())
    read_particle_file(particle_file, src.density, p);
  else
  {
    src.save_file = particle_file;
    generate_particles(src, p);
  }
  const double packing_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  BondMaterial mat;
  mat.model = bond_model_from_name(model_name);
  mat.youngs_modulus = 4e9;
  mat.poisson_ratio = 0.3;
  BondStore b;
  b.drop_force_records(); // as an explicit run's store (CaseConfig::run.bond_force_records)
  if (!(multiplier > 0))
    multiplier = packing == "hcp" ? 1.0 : 1.04;
  form_bonds(p, b, mat, multiplier);
  assign_bond_damping(p, b, damping);
  std::mt19937 rng(12345);
  std::normal_distribution<double> n01(0, 1);
  for (std::size_t i = 0; i < p.size(); ++i)
    p.velocity[i] = 1e-3 * Vec3(n01(rng), n01(rng), n01(rng));
  if (renumber)
    renumber_spatially(p, b);
  const double dt = 0.8 * estimate_critical_time_step(p, b).critical();
  const double setup = std::chrono::duration<double>(clock::now() - t0).count();
  const double nb = double(b.size()), np = double(p.size());

  nlohmann::json j;
  j["benchmark"] = packing + "_explicit";
  j["packing"] = packing;
  j["radius"] = radius;
  j["renumbered"] = renumber;
  j["bond_model"] = model_name;
  j["contact_radius_multiplier"] = multiplier;
  j["bond_damping_ratio"] = damping;
  j["n_particles"] = p.size();
  j["n_bonds"] = b.size();
  j["steps_per_round"] = steps;
  j["rounds"] = rounds;
  j["packing_seconds"] = packing_seconds;
  j["loadavg_1min_at_start"] = load_average;
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["setup_seconds"] = setup;
  for (int threads : thread_counts)
  {
    ParticleStore pf = p;
    BondStore bf = b;
    ExplicitSolver solver(pf, bf, {}, {}, {}, {dt, 0.0, threads});
    std::unique_ptr<PlainBondLoop> reference;
    if (plain)
      reference = std::make_unique<PlainBondLoop>(p, b, dt, threads);
    for (int s = 0; s < 5; ++s) // warm-up: page in, settle thread pools
    {
      solver.step(false);
      if (reference)
        reference->step();
    }
    std::vector<Timing> full, ref;
    for (int r = 0; r < rounds; ++r)
    {
      full.push_back(time_steps([&] { solver.step(false); }, steps));
      if (reference)
        ref.push_back(time_steps([&] { reference->step(); }, steps));
    }
    solver.step(true);
    nlohmann::json run;
    run["threads"] = threads;
    run["full"] = rates(full, nb, np, steps);
    run["full"]["energy_balance_error"] = solver.energy().relative_error();
    if (reference)
    {
      run["plain"] = rates(ref, nb, np, steps);
      std::vector<double> ratio; // per round: the two loops side by side in time
      for (int r = 0; r < rounds; ++r)
        ratio.push_back(ref[r].wall / full[r].wall);
      run["ratio_full_to_plain_median"] = median(ratio);
      run["ratio_full_to_plain_best"] = run["full"]["bond_updates_per_second"].get<double>() /
                                        run["plain"]["bond_updates_per_second"].get<double>();
      run["plain_memory_bytes_per_particle"] = double(reference->memory_bytes()) / np;
      run["plain_max_speed"] = reference->max_speed(); // finite, ~1e-3 m/s: stable
      run["full_max_speed"] = solver.max_speed();
    }
    if (threads == thread_counts.front())
    {
      // the stores as bond formation and renumbering leave them (capacity, not size: growth
      // slack counts), and the solver's own arrays
      nlohmann::json m;
      m["particles"] = double(p.memory_bytes()) / np;
      m["bonds"] = double(b.memory_bytes()) / np;
      m["solver"] = double(solver.memory_bytes()) / np;
      m["total"] = double(p.memory_bytes() + b.memory_bytes() + solver.memory_bytes()) / np;
      m["bonds_per_particle"] = nb / np;
      m["bytes_per_bond"] = double(b.memory_bytes()) / nb;
      // what the static run and coupled runs add: the per-bond force records (48 bytes a bond)
      m["bond_force_records_if_kept"] = double(2 * sizeof(Vec3)) * nb / np;
      j["bytes_per_particle"] = m;
    }
    j["runs"].push_back(run);
  }
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  j["peak_rss_bytes"] = double(usage.ru_maxrss) * 1024.0;
  std::cout << j.dump() << std::endl;
  if (!json_file.empty())
    std::ofstream(json_file) << j.dump(2) << '\n';
  return 0;
}
