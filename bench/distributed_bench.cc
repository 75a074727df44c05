// distributed-bench: the explicit DEM core on MPI ranks (distributed/) beside threads, in one run.
//   mpirun -np 2 build/bench/distributed-bench --radius 0.74e-3 --steps 10 --rounds 3 --json F
// The specimen is dembridge-bench's: the 0.25 x 0.1 x 0.1 m box of HCP spheres (r = 0.74 mm: a
// million), every touching pair bonded (TBBM, dashpots xi = 0.05), renumbered along a
// space-filling curve, seeded random velocities. First rank 0 alone steps dem's ExplicitSolver on
// 1 and on 2 threads (the other ranks sleep in a polled barrier, so that they leave the cores
// free); then every rank steps its part (distributed::DistributedSolver, one thread a rank). Per
// rank: particles, ghosts, bonds held, the doubles and messages of the per-step ghost exchange,
// bytes per owned particle (distributed_particles.h: memory_bytes, with the local solver's), and
// the shares of its time in the local step, the ghost exchange and the motion checks
// (DistributedSolver::timings). Rates per wall second (best and median of the rounds) and per
// CPU-second of the process(es) (median). Prints one JSON object on rank 0.
#include "dem/bonds/bonding.h"
#include "dem/model/renumbering.h"
#include "dem/packing/packings.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/time_step.h"
#include "distributed/distributed_solver.h"
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <ctime>
#include <deal.II/base/mpi.h>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>
#include <unistd.h>

using namespace dembridge;
using dem::Vec3;
using clock_type = std::chrono::steady_clock;

namespace
{
double seconds_since(clock_type::time_point t0)
{
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

/// CPU seconds of this process, all its threads: on a shared machine a rate per CPU-second is
/// not diluted by other processes holding the cores (wall rates are).
double cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// A barrier that sleeps while it waits (an MPI_Barrier spins and would take a core from the
/// threads measured meanwhile).
void sleeping_barrier(MPI_Comm comm)
{
  MPI_Request request;
  MPI_Ibarrier(comm, &request);
  int done = 0;
  while (!done)
  {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (!done)
      usleep(2000);
  }
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

dem::Model specimen(double radius, double damping)
{
  dem::Model m;
  dem::ParticleSource src;
  src.kind = dem::ParticleSource::Kind::hcp;
  src.radius = radius;
  src.box_size = Vec3(0.25, 0.1, 0.1);
  dem::generate_particles(src, m.particles);
  dem::BondMaterial mat;
  mat.youngs_modulus = 4e9;
  m.bonds.drop_force_records();
  dem::form_bonds(m.particles, m.bonds, mat, 1.0);
  dem::assign_bond_damping(m.particles, m.bonds, damping);
  std::mt19937 rng(12345);
  std::normal_distribution<double> n01(0, 1);
  for (auto& v : m.particles.velocity)
    v = 1e-3 * Vec3(n01(rng), n01(rng), n01(rng));
  dem::renumber_spatially(m.particles, m.bonds);
  m.critical = dem::estimate_critical_time_step(m.particles, m.bonds);
  m.time_step = 0.8 * m.critical.critical();
  return m;
}
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm = MPI_COMM_WORLD;
  const unsigned rank = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  CLI::App app{"distributed-bench: the DEM core on MPI ranks beside threads"};
  double radius = 2.5e-3, damping = 0.05;
  int steps = 20, rounds = 3;
  std::string json_file;
  app.add_option("--radius", radius, "Particle radius (m)")->check(CLI::PositiveNumber);
  app.add_option("--damping", damping, "Bond dashpot damping ratio")->check(CLI::Range(0.0, 1.0));
  app.add_option("--steps", steps, "Time steps per round")->check(CLI::Range(1, 100000));
  app.add_option("--rounds", rounds, "Rounds")->check(CLI::Range(1, 100));
  app.add_option("--json", json_file, "Also write the result to this file");
  CLI11_PARSE(app, argc, argv);

  double load_average = -1;
  std::ifstream("/proc/loadavg") >> load_average;
  auto t0 = clock_type::now();
  dem::Model model = specimen(radius, damping);
  const double setup = seconds_since(t0);
  const double nb = double(model.bonds.size());
  nlohmann::json j;
  j["benchmark"] = "hcp_explicit_ranks";
  j["radius"] = radius, j["bond_damping_ratio"] = damping;
  j["n_particles"] = model.particles.size(), j["n_bonds"] = model.bonds.size();
  j["steps_per_round"] = steps, j["rounds"] = rounds, j["ranks"] = n_ranks;
  j["loadavg_1min_at_start"] = load_average;
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["setup_seconds_per_rank"] = setup;

  // 1 and 2 threads on rank 0 alone, the rounds alternating
  if (rank == 0)
  {
    dem::ParticleStore p1 = model.particles, p2 = model.particles;
    dem::BondStore b1 = model.bonds, b2 = model.bonds;
    dem::ExplicitSolver one(p1, b1, {}, {}, {}, {model.time_step, 0.0, 1});
    dem::ExplicitSolver two(p2, b2, {}, {}, {}, {model.time_step, 0.0, 2});
    one.step(), two.step();
    std::vector<double> rate1, rate2, cpu_rate1, cpu_rate2;
    for (int r = 0; r < rounds; ++r)
    {
      t0 = clock_type::now();
      double c0 = cpu_seconds();
      for (int s = 0; s < steps; ++s)
        one.step();
      rate1.push_back(nb * steps / seconds_since(t0));
      cpu_rate1.push_back(nb * steps / (cpu_seconds() - c0));
      t0 = clock_type::now();
      c0 = cpu_seconds();
      for (int s = 0; s < steps; ++s)
        two.step();
      rate2.push_back(nb * steps / seconds_since(t0));
      cpu_rate2.push_back(nb * steps / (cpu_seconds() - c0));
    }
    j["threads_1"] = {{"bond_updates_per_second", *std::max_element(rate1.begin(), rate1.end())},
                      {"median", median(rate1)},
                      {"per_cpu_second_median", median(cpu_rate1)}};
    j["threads_2"] = {{"bond_updates_per_second", *std::max_element(rate2.begin(), rate2.end())},
                      {"median", median(rate2)},
                      {"per_cpu_second_median", median(cpu_rate2)}};
  }
  sleeping_barrier(comm);

  // every rank its part, one thread each
  t0 = clock_type::now();
  distributed::DistributedSolver ranks(model, {model.time_step, 0.0, 1}, comm);
  const double distribute = seconds_since(t0);
  auto& part = ranks.particles();
  ranks.step();
  std::vector<double> rate, cpu(std::size_t(rounds), 0.0);
  for (int r = 0; r < rounds; ++r)
  {
    MPI_Barrier(comm);
    t0 = clock_type::now();
    const double c0 = cpu_seconds();
    for (int s = 0; s < steps; ++s)
      ranks.step();
    cpu[std::size_t(r)] = cpu_seconds() - c0;
    MPI_Barrier(comm);
    rate.push_back(nb * steps / seconds_since(t0));
  }
  // per CPU-second of all ranks together (an MPI wait that polls counts as CPU time)
  MPI_Allreduce(MPI_IN_PLACE, cpu.data(), rounds, MPI_DOUBLE, MPI_SUM, comm);
  std::vector<double> cpu_rate;
  for (const double c : cpu)
    cpu_rate.push_back(nb * steps / c);
  // per rank
  const dem::ParticleStore& p = part.particles();
  long held = long(part.bonds().size()), booked = 0;
  for (std::size_t k = 0; k < part.bonds().size(); ++k)
    booked += std::size_t(part.bonds().a[k]) < part.n_owned();
  const double bytes = double(part.memory_bytes() + ranks.local().memory_bytes());
  const auto& t = ranks.timings();
  const double total = t.local_step + t.ghosts + t.motion_checks + t.rebuilds + t.records;
  const std::vector<double> mine = {double(part.n_owned()),
                                    double(p.size() - part.n_owned()),
                                    double(held),
                                    double(booked),
                                    double(part.halo_doubles()),
                                    double(part.halo_targets()),
                                    bytes / double(std::max<std::size_t>(1, part.n_owned())),
                                    t.local_step / total,
                                    t.ghosts / total,
                                    t.motion_checks / total,
                                    double(ranks.steps()),
                                    double(p.memory_bytes()) / double(part.n_owned()),
                                    double(part.bonds().memory_bytes()) / double(part.n_owned()),
                                    double(ranks.local().memory_bytes()) / double(part.n_owned()),
                                    double(part.handler_bytes()) / double(part.n_owned()),
                                    double(part.mesh_bytes()) / double(part.n_owned())};
  const auto all = dealii::Utilities::MPI::gather(comm, mine, 0);
  if (rank == 0)
  {
    j["ranks_run"] = {{"bond_updates_per_second", *std::max_element(rate.begin(), rate.end())},
                      {"median", median(rate)},
                      {"per_cpu_second_median", median(cpu_rate)},
                      {"distribute_seconds", distribute}};
    for (const auto& r : all)
      j["per_rank"].push_back({{"owned", r[0]},
                               {"ghosts", r[1]},
                               {"bonds_held", r[2]},
                               {"bonds_booked", r[3]},
                               {"halo_doubles_per_step", r[4]},
                               {"halo_bytes_per_step", 8 * r[4]},
                               {"halo_messages_per_step", r[5]},
                               {"bytes_per_owned_particle", r[6]},
                               {"time_share_local_step", r[7]},
                               {"time_share_ghost_exchange", r[8]},
                               {"time_share_motion_checks", r[9]},
                               {"steps", r[10]},
                               {"bytes_per_owned_particle_parts",
                                {{"particle_store", r[11]},
                                 {"bond_store", r[12]},
                                 {"solver", r[13]},
                                 {"handler_particles", r[14]},
                                 {"background_mesh", r[15]},
                                 {"rest", r[6] - r[11] - r[12] - r[13] - r[14] - r[15]}}}});
    if (j.contains("threads_1"))
    {
      const double one = j["threads_1"]["bond_updates_per_second"];
      j["ranks_over_one_thread"] = j["ranks_run"]["bond_updates_per_second"].get<double>() / one;
      j["ranks_over_threads"] = j["ranks_run"]["bond_updates_per_second"].get<double>() /
                                j["threads_2"]["bond_updates_per_second"].get<double>();
    }
    std::cout << j.dump() << std::endl;
    if (!json_file.empty())
      std::ofstream(json_file) << j.dump(2) << '\n';
  }
  return 0;
}
