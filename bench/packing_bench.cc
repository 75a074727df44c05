// packing-bench: time of the random close packing (dem/packing/packing_random.h) against the
// particle count. The box is the thesis specimen (0.25 x 0.1 x 0.1 m, thesis section 4.1); the
// sphere count is set by the radius (r = 5 mm: ~2,900 spheres, 2.5 mm: ~23,000, 0.7 mm: ~1 M).
// For each radius: wall and CPU time, relaxation iterations, porosity, coordination (contact
// multiplier 1.02) and a fingerprint of the packing (FNV-1a over the bits of every centre and
// radius), so that two builds can be checked to give bitwise the same packing. With
// --threads 1,2 each radius is packed once per thread count in the same run (wall time is what
// threads save; the fingerprints must agree), and with --rounds N that N times, the thread
// counts alternating, with the best and median wall time of each in "summary" (this 2-vCPU VM
// sometimes runs two threads at half speed: the host's placement, not the code).
// Prints one JSON object (and writes it with --json).
#include "dem/packing/packing_random.h"
#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstring>
#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <time.h>

using namespace dembridge::dem;

namespace
{
double process_cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// FNV-1a over the bit patterns of every centre and radius, as 16 hex digits.
std::string fingerprint(const ParticleStore& p)
{
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](double v)
  {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int k = 0; k < 8; ++k)
    {
      h ^= (bits >> (8 * k)) & 0xffu;
      h *= 1099511628211ull;
    }
  };
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    for (int d = 0; d < 3; ++d)
      mix(p.position[i][d]);
    mix(p.radius[i]);
  }
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}
} // namespace

int main(int argc, char** argv)
{
  CLI::App app{"packing-bench: random close packing time against the particle count"};
  std::vector<double> radii = {5e-3, 2.5e-3};
  unsigned seed = 1;
  std::string json_file, csv_file;
  double spread = 0;
  app.add_option("--radii", radii, "Mean radii (m), one packing each")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "Packing seed");
  app.add_option("--uniform-spread", spread, "Uniform radius spread (0: equal spheres)")
      ->check(CLI::Range(0.0, 0.9));
  app.add_option("--json", json_file, "Also write the result to this file");
  app.add_option("--csv", csv_file, "Write the (last) packing to this particle file");
  double target_porosity = RandomPackingSettings().target_porosity;
  app.add_option("--target-porosity", target_porosity, "Target porosity of every packing")
      ->check(CLI::Range(0.0, 1.0));
  int rounds = 1;
  app.add_option("--rounds", rounds, "Packings per radius and thread count")
      ->check(CLI::Range(1, 100));
  std::vector<int> thread_counts = {1};
  app.add_option("--threads", thread_counts, "Thread counts, one packing each per radius")
      ->check(CLI::Range(1, 256));
  bool predict = false;
  app.add_flag("--predict-jamming", predict,
               "The jamming porosity predicted from the box, not measured by a first pass "
               "(RandomPackingSettings::predict_jamming)");
  CLI11_PARSE(app, argc, argv);

  nlohmann::json out;
  out["benchmark"] = "random close packing, thesis specimen 0.25 x 0.1 x 0.1 m";
  out["seed"] = seed;
  out["distribution"] = spread > 0 ? "uniform" : "mono";
  out["radius_spread"] = spread;
  out["jamming_estimate"] = predict ? "predicted" : "measured";
  out["target_porosity"] = target_porosity;
  for (double r : radii)
  {
    std::map<int, std::vector<double>> walls;
    std::set<std::string> fingerprints;
    for (int round = 1; round <= rounds; ++round)
      for (int threads : thread_counts)
      {
        RandomPackingSettings s;
        s.mean_radius = r;
        s.seed = seed;
        s.predict_jamming = predict;
        s.threads = threads;
        s.target_porosity = target_porosity;
        if (spread > 0)
        {
          s.distribution = RandomPackingSettings::Distribution::uniform;
          s.radius_spread = spread;
        }
        ParticleStore p;
        const double c0 = process_cpu_seconds();
        const RandomPackingReport rep = generate_random_packing(s, 917, p);
        const double cpu = process_cpu_seconds() - c0;
        nlohmann::json j;
        j["radius_m"] = r;
        j["threads"] = threads;
        j["round"] = round;
        j["particles"] = rep.particles;
        j["removed"] = rep.removed;
        j["wall_seconds"] = rep.seconds;
        j["cpu_seconds"] = cpu;
        j["iterations"] = rep.iterations;
        j["microseconds_per_particle_iteration"] =
            1e6 * cpu / (double(rep.particles) * double(rep.iterations));
        j["wall_microseconds_per_particle_iteration"] =
            1e6 * rep.seconds / (double(rep.particles) * double(rep.iterations));
        j["porosity"] = rep.porosity;
        j["coordination_1.02"] = rep.mean_coordination_contact;
        j["max_overlap_ratio"] = rep.max_overlap_ratio;
        j["radius_scale"] = rep.radius_scale;
        j["fingerprint"] = fingerprint(p);
        std::cerr << j.dump() << "\n";
        out["points"].push_back(j);
        if (!csv_file.empty())
          write_particle_file(csv_file, p);
        walls[threads].push_back(rep.seconds);
        fingerprints.insert(j["fingerprint"].get<std::string>());
      }
    for (auto& [threads, w] : walls)
    {
      std::sort(w.begin(), w.end());
      out["summary"].push_back({{"radius_m", r},
                                {"threads", threads},
                                {"rounds", w.size()},
                                {"best_wall_seconds", w.front()},
                                {"median_wall_seconds", w[w.size() / 2]},
                                {"speedup_best_vs_fewest_threads",
                                 walls.begin()->second.front() / w.front()},
                                {"one_fingerprint", fingerprints.size() == 1}});
    }
  }
  std::cout << out.dump(2) << "\n";
  if (!json_file.empty())
    std::ofstream(json_file) << out.dump(2) << "\n";
  return 0;
}
