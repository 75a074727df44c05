#pragma once
// dembridge elasticity CASE.prm [--set ...] [--output-dir DIR]: the packing's own stiffness
// tensor (dem/measurements/elasticity_tensor.h). Builds the DEM model of the case,
// measures the 6x6 tensor of the specimen's core under six uniform strains (static solver) and,
// for lattice sources (cubic, hcp, fcc), the ideal lattice's tensor from one periodic cell;
// writes DIR/elasticity.json (default output/elasticity_<case stem>) atomically and prints a
// short table. elasticity.json (SI units, Voigt order xx, yy, zz, yz, xz, xy, engineering shear
// strains):
//   stiffness_tensor (6x6, Pa), compliance (6x6, 1/Pa), youngs_modulus {x, y, z},
//   poisson_ratio {xy, xz, yx, yz, zx, zy} (nu_ij = -eps_j / eps_i under stress along i),
//   shear_modulus {yz, xz, xy}, anisotropy {universal_index, zener_ratio, bulk/shear moduli
//   Voigt and Reuss}, measurement {core box, counts, symmetry error, ...}, n_particles, n_bonds,
//   and for lattices periodic_stiffness_tensor (6x6) with periodic {the same derived fields,
//   cell_volume, particles_per_cell, bonds_per_cell, coordination}; for columnar cases columns
//   {boundary_area_per_volume, cells, and with --interface-estimate the estimate of E across
//   the columns and its inputs} (column_estimate.h).
#include "dem/measurements/elasticity_tensor.h"
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace dembridge::app
{
struct ElasticityOptions
{
  std::string case_file;
  std::vector<std::string> overrides; ///< --set "Section/Key=value"
  std::string output_dir;             ///< empty: output/elasticity_<case stem>
  double core_margin = dem::ElasticityMeasurementSettings{}.core_margin;
  double boundary_thickness = dem::ElasticityMeasurementSettings{}.boundary_thickness;
  /// columnar cases: also the interface-compliance estimate across the columns (column_estimate.h)
  bool interface_estimate = false;
};

/// Declares the subcommand and its options on @p app.
CLI::App* add_elasticity_command(CLI::App& app, ElasticityOptions& options);

/// The measurement of a case's packing (read with its overrides, paths relative to the case
/// file): the specimen's measured tensor and, for lattices, the periodic cell's. Throws
/// std::runtime_error "<case file>: <Section/key or what>: <reason>" on bad input.
nlohmann::json measure_elasticity(const ElasticityOptions& options);

/// The JSON object of a tensor's derived fields (stiffness_tensor, compliance, youngs_modulus,
/// poisson_ratio, shear_modulus, anisotropy).
nlohmann::json elasticity_json(const dem::ElasticProperties& properties);

/// Runs the subcommand: measure, write elasticity.json, print the table; returns the exit code.
int run_elasticity(const ElasticityOptions& options);
} // namespace dembridge::app
