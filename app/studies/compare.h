#pragma once
// dembridge compare COUPLED_CASE.prm: the coupled run against full DEM and a full (elastic) FE
// model of the same geometry, supports, load and packing (coupling/full_models.h derives the
// two), and for a case with an adaptive region the same coupled case with the region it ended
// with fixed from the start (coupling/fixed_region.h). The runs go into the output folder D:
//   D/coupled/    the coupled run of the case
//   D/coupled_fixed/  adaptive cases: coupled_fixed.prm (the adaptive region off, the particle
//                 region coupled_fixed_region.msh: the adaptive run's final cells) and its run
//   D/full_dem/   full_dem.prm (the derived DEM case, runnable) and its run (the coupled run's
//                 time step, so that both march alike)
//   D/full_fem/   the static FE run (in this process)
//   D/comparison.json   per model: wall time, peak memory, peak load, deflection at peak,
//                       initial stiffness, broken bonds, fracture energy, first crack, energy
//                       balance (and the adaptive run's growth figures); each pair against full
//                       DEM (and adaptive against fixed): ratios, the first cracks' distance,
//                       the speed-up
//   D/comparison.csv    the load-deflection curves (model, deflection, load)
//   D/comparison.png    the curves and the crack paths side by side (broken-bond midpoints
//                       projected on the beam's side), matplotlib via /usr/bin/python3
// The particle runs are `dembridge run` in processes of their own, started from argument vectors
// (compare_process.h: each model's peak memory is its own). Every input is checked (the derived
// models built on paper) before anything runs; comparison.json is written last, so a failed
// comparison leaves none.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace dembridge::app
{
struct CompareOptions
{
  std::string case_file, output_dir;
  std::vector<std::string> overrides;
  double fe_cell_size = 0;    ///< m; 0: two particle diameters
  unsigned int fe_degree = 2; ///< FE_Q degree of the elastic reference
  bool plot = true;
};

CLI::App* add_compare_command(CLI::App& app, CompareOptions& o);
int run_compare(const CompareOptions& o);
} // namespace dembridge::app
