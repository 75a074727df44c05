// static-bench: the quasi-static solver's linear solve against the particle count, Jacobi CG
// (Eigen, dem/solvers/static_solver.cc) beside CG + GAMG (PETSc, fem/bond_network_solver.h) on
// the same model in the same run. The case is the thesis compression test on the 0.25 x 0.1 x
// 0.1 m specimen (tests/fem/compression_case.h), as an HCP lattice or a random close packing;
// the radius sets the particle count (HCP: r = 2.5 mm ~ 25.6 k, 0.74 mm ~ 1 M). Both solves stop
// at the same relative residual of the scaled system. Prints one JSON object (--json writes it).
#include "compression_case.h"
#include "dem/solvers/static_solver.h"
#include "fem/bond_network_solver.h"
#include <CLI/CLI.hpp>
#include <chrono>
#include <deal.II/base/mpi.h>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <time.h>

using namespace dembridge;

namespace
{
/// CPU time of the process, s: on a machine shared with other jobs the reproducible figure.
double process_cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double peak_rss_gib()
{
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / (1024.0 * 1024.0); // ru_maxrss is in KiB on Linux
}
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1); // initialises PETSc
  CLI::App app{"static-bench: Jacobi CG against CG + GAMG on the thesis compression test"};
  std::vector<double> radii = {2.5e-3};
  std::string packing = "hcp", json_file;
  std::vector<std::string> solvers = {"cg", "gamg"};
  double tolerance = 1e-10;
  long cg_limit = 2000000;
  bool predict = false;
  app.add_option("--radii", radii, "Particle radii (m), one model each")
      ->check(CLI::PositiveNumber);
  app.add_option("--packing", packing, "hcp or random")->check(CLI::IsMember({"hcp", "random"}));
  app.add_option("--solvers", solvers, "cg and/or gamg")->check(CLI::IsMember({"cg", "gamg"}));
  app.add_option("--tolerance", tolerance, "Relative residual of the scaled system");
  app.add_option("--cg-particle-limit", cg_limit,
                 "Skip Jacobi CG above this many particles (its time grows as N^(4/3))");
  app.add_option("--json", json_file, "Also write the result to this file");
  app.add_flag("--predict-jamming", predict,
               "Random packings by the predicted jamming estimate (one pass; default: measured, "
               "whose packings the recorded figures rest on)");
  CLI11_PARSE(app, argc, argv);

  using clock = std::chrono::steady_clock;
  nlohmann::json out;
  out["benchmark"] = "quasi-static compression test, thesis specimen 0.25 x 0.1 x 0.1 m, TBBM";
  out["packing"] = packing;
  out["tolerance"] = tolerance;
  out["jamming_estimate"] = predict ? "predicted" : "measured";
  for (double r : radii)
  {
    const auto t0 = clock::now();
    dem::CaseConfig config = test::compression_case(
        packing == "hcp" ? dem::ParticleSource::Kind::hcp : dem::ParticleSource::Kind::random, r);
    // why: the recorded figures (README) rest on the measured estimate's packings
    config.particles.predict_jamming = predict;
    dem::Model model = dem::build_model(config);
    nlohmann::json point;
    point["radius_m"] = r;
    point["particles"] = model.particles.size();
    point["bonds"] = model.bonds.size();
    point["build_seconds"] = std::chrono::duration<double>(clock::now() - t0).count();
    for (const std::string& solver : solvers)
    {
      if (solver == "cg" && long(model.particles.size()) > cg_limit)
        continue;
      dem::StaticSettings s;
      s.method = dem::StaticSettings::Method::cg_jacobi;
      s.cg_tolerance = tolerance;
      if (solver == "gamg")
        s.iterative_solver = fem::gamg_iterative_solver();
      // why: the solve starts from the reference state, so one model serves both solvers
      const double c0 = process_cpu_seconds();
      const dem::StaticResult res = dem::solve_static(model, s);
      const double cpu = process_cpu_seconds() - c0;
      nlohmann::json j;
      j["method"] = res.method;
      j["unknowns"] = res.n_free_dofs;
      j["iterations"] = res.iterations;
      j["assembly_seconds"] = res.assembly_seconds;
      j["solve_seconds"] = res.solve_seconds;
      j["setup_seconds"] = res.setup_seconds;
      j["cpu_seconds"] = cpu; // assembly + solve
      j["residual"] = res.residual;
      j["modulus_pa"] = test::compression_modulus(model);
      j["peak_rss_gib"] = peak_rss_gib(); // of the process so far
      std::cerr << "r = " << r << " m, " << model.particles.size() << " particles, " << solver
                << ": " << j.dump() << "\n";
      point[solver] = j;
    }
    out["points"].push_back(point);
    if (!json_file.empty()) // why: a later, larger point may run out of time or memory
      std::ofstream(json_file) << out.dump(2) << "\n";
  }
  std::cout << out.dump(2) << "\n";
  return 0;
}
