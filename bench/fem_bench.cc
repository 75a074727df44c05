// fem-bench: times the static FE solver on the cantilever of examples/fem_cantilever.prm
// (1 x 0.1 x 0.1 m, clamped at x = 0, 100 N down on the free end face, E = 4 GPa, nu = 0.3) at
// a requested number of DoFs: mesh generation + DoF setup, assembly, AMG setup, CG solve, CG
// iterations and peak memory per rank. One JSON object per run (stdout, and --json FILE).
//   mpirun -np 2 fem-bench --degree 2 --dofs 1e6 --json out.json
// The mesh is 10n x n x n cells with n chosen so that 3 (10 n p + 1)(n p + 1)^2 is nearest to
// --dofs (p = degree).
#include "fem/elastic_problem.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
/// Peak resident set size of this process (VmHWM), bytes.
double peak_rss_bytes()
{
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key)
  {
    if (key == "VmHWM:")
    {
      double kb = 0;
      in >> kb;
      return kb * 1024.0;
    }
    in.ignore(1024, '\n');
  }
  return 0;
}

unsigned int cells_for(double dofs, unsigned int degree)
{
  unsigned int best = 1;
  double best_error = 1e300;
  for (unsigned int n = 1; n < 400; ++n)
  {
    const double p = degree;
    const double d = 3.0 * (10 * n * p + 1) * (n * p + 1) * (n * p + 1);
    if (std::abs(std::log(d / dofs)) < best_error)
      best_error = std::abs(std::log(d / dofs)), best = n;
  }
  return best;
}
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  CLI::App app{"fem-bench: static FE solver timing (cantilever, CG + BoomerAMG)"};
  unsigned int degree = 1;
  double dofs = 1e5, tolerance = 1e-8;
  std::string json_file;
  app.add_option("--degree", degree, "FE degree (1 or 2)")->check(CLI::Range(1, 2));
  app.add_option("--dofs", dofs, "Target number of DoFs")->check(CLI::PositiveNumber);
  app.add_option("--tolerance", tolerance, "CG relative residual tolerance");
  app.add_option("--json", json_file, "Also write the result to this file");
  CLI11_PARSE(app, argc, argv);

  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  try
  {
    using namespace dembridge::fem;
    Parameters p;
    p.degree = degree;
    p.mesh_source = MeshSource::box;
    p.box_lower = Point<3>(0, 0, 0);
    p.box_upper = Point<3>(1.0, 0.1, 0.1);
    const unsigned int n = cells_for(dofs, degree);
    p.subdivisions = {{10 * n, n, n}};
    p.youngs_modulus = 4e9;
    p.poisson_ratio = 0.3;
    p.boundary_constraints.push_back({"x-min", {{true, true, true}}, 0.0});
    Tensor<1, 3> force;
    force[2] = -100;
    p.boundary_forces.push_back({"x-max", force});
    p.solver_tolerance = tolerance;
    p.max_iterations = 10000;
    p.write_vtu = false;

    const auto start = std::chrono::steady_clock::now();
    ElasticProblem problem(p, comm);
    problem.make_grid();
    problem.setup_system();
    problem.assemble_system(true);
    const unsigned int iterations = problem.solve();
    const double total =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    auto times = problem.timer().get_summary_data(dealii::TimerOutput::total_wall_time);
    auto seconds = [&](const std::string& section)
    { return dealii::Utilities::MPI::max(times.count(section) ? times[section] : 0.0, comm); };
    const double rss = peak_rss_bytes();
    nlohmann::json j;
    j["problem"] = "cantilever 1 x 0.1 x 0.1 m, clamped, end load; CG + BoomerAMG";
    j["degree"] = degree;
    j["n_ranks"] = dealii::Utilities::MPI::n_mpi_processes(comm);
    j["cells"] = {10 * n, n, n};
    j["n_cells"] = problem.n_cells();
    j["n_dofs"] = problem.n_dofs();
    j["cg_iterations"] = iterations;
    j["cg_tolerance"] = tolerance;
    j["setup_seconds"] = seconds("make grid") + seconds("setup system");
    j["assembly_seconds"] = seconds("assemble system");
    j["amg_setup_seconds"] = seconds("amg setup");
    j["cg_seconds"] = seconds("solve") - seconds("amg setup");
    j["solve_seconds"] = seconds("solve");
    j["total_seconds"] = dealii::Utilities::MPI::max(total, comm);
    j["peak_rss_bytes_max_rank"] = dealii::Utilities::MPI::max(rss, comm);
    j["peak_rss_bytes_all_ranks"] = dealii::Utilities::MPI::sum(rss, comm);
    if (root)
    {
      std::cout << j.dump() << std::endl;
      if (!json_file.empty())
      {
        std::ofstream out(json_file);
        out << j.dump(2) << '\n';
      }
    }
  }
  catch (const std::exception& e)
  {
    if (root)
      std::cerr << "fem-bench: error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
