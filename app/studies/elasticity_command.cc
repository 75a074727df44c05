// dembridge elasticity: the packing's own stiffness tensor (see elasticity_command.h).
#include "app/studies/elasticity_command.h"
#include "app/input/case_file.h"
#include "app/input/dem_parameters.h"
#include "app/studies/column_estimate.h"
#include "app/studies/verify.h"
#include "app/studies/verify_report.h"
#include "dem/model/model.h"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace dembridge::app
{
namespace fs = std::filesystem;
using nlohmann::json;

namespace
{
json matrix_json(const dem::Matrix6& m)
{
  json rows = json::array();
  for (int i = 0; i < 6; ++i)
  {
    json row = json::array();
    for (int j = 0; j < 6; ++j)
      row.push_back(m(i, j));
    rows.push_back(row);
  }
  return rows;
}

json vec_json(const dem::Vec3& v)
{
  return {v.x(), v.y(), v.z()};
}
} // namespace

json elasticity_json(const dem::ElasticProperties& p)
{
  const char* axis = "xyz";
  json j;
  j["stiffness_tensor"] = matrix_json(p.stiffness);
  j["compliance"] = matrix_json(p.compliance);
  j["youngs_modulus"] = {
      {"x", p.youngs_modulus.x()}, {"y", p.youngs_modulus.y()}, {"z", p.youngs_modulus.z()}};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      if (i != k)
        j["poisson_ratio"][std::string{axis[i], axis[k]}] = p.poisson_ratio(i, k);
  j["shear_modulus"] = {
      {"yz", p.shear_modulus[0]}, {"xz", p.shear_modulus[1]}, {"xy", p.shear_modulus[2]}};
  j["anisotropy"] = {{"universal_index", p.universal_anisotropy},
                     {"zener_ratio", p.zener_ratio},
                     {"bulk_modulus_voigt", p.bulk_modulus_voigt},
                     {"bulk_modulus_reuss", p.bulk_modulus_reuss},
                     {"shear_modulus_voigt", p.shear_modulus_voigt},
                     {"shear_modulus_reuss", p.shear_modulus_reuss}};
  return j;
}

CLI::App* add_elasticity_command(CLI::App& app, ElasticityOptions& o)
{
  auto* cmd = app.add_subcommand(
      "elasticity",
      "Measure the 6x6 stiffness tensor of a case's bonded packing (elasticity.json)");
  cmd->add_option("case", o.case_file, "DEM case file")->required();
  cmd->add_option("--set", o.overrides, "Override a parameter: \"Section/Key=value\"");
  cmd->add_option("--output-dir", o.output_dir, "Output folder (default output/elasticity_CASE)");
  cmd->add_option("--core-margin", o.core_margin,
                  "Core (RVE): centres at least this many mean diameters from every face")
      ->capture_default_str();
  cmd->add_option("--boundary-thickness", o.boundary_thickness,
                  "Held layer: centres within this many radii of a face")
      ->capture_default_str();
  cmd->add_flag("--interface-estimate", o.interface_estimate,
                "Columnar cases: also the interface-compliance estimate of E across the columns "
                "(one-plane specimens and the packing without grains: about 90 more solves)");
  return cmd;
}

json measure_elasticity(const ElasticityOptions& o)
{
  const std::string case_name = fs::path(o.case_file).filename().string();
  if (!(o.core_margin >= 0) || !std::isfinite(o.core_margin))
    throw std::runtime_error("--core-margin: must be a non-negative number of diameters");
  if (!(o.boundary_thickness > 0) || !std::isfinite(o.boundary_thickness))
    throw std::runtime_error("--boundary-thickness: must be a positive number of radii");
  auto prm = read_case(o.case_file, o.overrides);
  if (prm->get("Mode") != "dem")
    throw std::runtime_error(case_name + ": Mode: elasticity needs a DEM case (Mode = dem)");
  json j;
  try
  {
    WorkingDirectory cd(fs::absolute(o.case_file).parent_path()); // case-relative paths
    const dem::CaseConfig config = parse_dem_case(*prm);
    const dem::Model model = dem::build_model(config);
    dem::ElasticityMeasurementSettings settings;
    settings.core_margin = o.core_margin;
    settings.boundary_thickness = o.boundary_thickness;
    const auto kind = config.particles.kind;
    settings.core_period = dem::lattice_axis_periods(kind, config.particles.radius);
    const dem::MeasuredElasticity m = dem::measured_stiffness_tensor(model, settings);

    j = elasticity_json(m.properties);
    j["n_particles"] = m.n_particles;
    j["n_bonds"] = m.n_bonds;
    j["measurement"] = {{"method",
                         "six affine strains on the held boundary layer, static solve; stress: RVE "
                         "average over the core (thesis eq. 54), strain: the core's least-squares "
                         "gradient; C = S E^-1, symmetrised"},
                        {"extent_lower", vec_json(m.extent_lo)},
                        {"extent_upper", vec_json(m.extent_hi)},
                        {"core_lower", vec_json(m.core_lo)},
                        {"core_upper", vec_json(m.core_hi)},
                        {"core_volume", m.core_volume},
                        {"core_margin_diameters", settings.core_margin},
                        {"core_period", vec_json(settings.core_period)},
                        {"boundary_thickness_radii", settings.boundary_thickness},
                        {"n_held", m.n_held},
                        {"n_core", m.n_core},
                        {"symmetry_error", m.symmetry_error},
                        {"stress_asymmetry", m.stress_asymmetry},
                        {"core_strain_deviation", m.core_strain_deviation},
                        {"max_residual", m.max_residual},
                        {"solve_seconds", m.solve_seconds}};
    if (config.microstructure.grains.enabled) // S_v, and the estimate on request
      j["columns"] = column_estimate_json(config, m, settings, o.interface_estimate);
    else if (o.interface_estimate)
      throw dem::InputError("--interface-estimate: the case has no columnar grains");
    if (settings.core_period.norm() > 0) // a lattice: the ideal one as well
    {
      const dem::PeriodicElasticity p = dem::periodic_stiffness_tensor(
          dem::lattice_cell(kind, config.particles.radius), config.bonds.material,
          config.bonds.contact_radius_multiplier);
      json periodic = elasticity_json(p.properties);
      j["periodic_stiffness_tensor"] = periodic["stiffness_tensor"];
      periodic.erase("stiffness_tensor");
      periodic["cell_volume"] = p.cell_volume;
      periodic["particles_per_cell"] = p.n_basis;
      periodic["bonds_per_cell"] = p.n_bonds_per_cell;
      periodic["coordination"] = p.mean_coordination;
      j["periodic"] = periodic;
    }
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(case_name + ": " + one_line(e.what()));
  }
  j["case"] = case_name;
  j["units"] = "Pa; Voigt order xx, yy, zz, yz, xz, xy; engineering shear strains";
  return j;
}

namespace
{
void print_table(const json& j)
{
  const bool periodic = j.contains("periodic_stiffness_tensor");
  const auto& m = j["measurement"];
  std::printf("%s: %ld particles, %ld bonds; core %ld particles (%.3g diameters from the faces)\n",
              j["case"].get<std::string>().c_str(), j["n_particles"].get<long>(),
              j["n_bonds"].get<long>(), m["n_core"].get<long>(),
              m["core_margin_diameters"].get<double>());
  std::printf("%-22s %14s%s\n", "", "measured", periodic ? "   periodic cell" : "");
  auto row = [&](const std::string& name, double measured, const json* other, double scale)
  {
    std::printf("%-22s %14.6g", name.c_str(), measured / scale);
    if (other)
      std::printf(" %15.6g", other->get<double>() / scale);
    std::printf("\n");
  };
  const json* per = periodic ? &j["periodic"] : nullptr;
  const char* names[6] = {"11", "22", "33", "44", "55", "66"};
  for (int i = 0; i < 6; ++i)
    row(std::string("C") + names[i] + " (GPa)", j["stiffness_tensor"][i][i].get<double>(),
        periodic ? &j["periodic_stiffness_tensor"][i][i] : nullptr, 1e9);
  for (const auto& [a, b] : {std::pair{0, 1}, {0, 2}, {1, 2}})
    row(std::string("C") + char('1' + a) + char('1' + b) + " (GPa)",
        j["stiffness_tensor"][a][b].get<double>(),
        periodic ? &j["periodic_stiffness_tensor"][a][b] : nullptr, 1e9);
  for (const char* k : {"x", "y", "z"})
    row(std::string("E_") + k + " (GPa)", j["youngs_modulus"][k].get<double>(),
        per ? &(*per)["youngs_modulus"][k] : nullptr, 1e9);
  for (const char* k : {"yz", "xz", "xy"})
    row(std::string("G_") + k + " (GPa)", j["shear_modulus"][k].get<double>(),
        per ? &(*per)["shear_modulus"][k] : nullptr, 1e9);
  for (const char* k : {"xy", "xz", "yz"})
    row(std::string("nu_") + k, j["poisson_ratio"][k].get<double>(),
        per ? &(*per)["poisson_ratio"][k] : nullptr, 1);
  row("anisotropy A^U", j["anisotropy"]["universal_index"].get<double>(),
      per ? &(*per)["anisotropy"]["universal_index"] : nullptr, 1);
  row("Zener ratio", j["anisotropy"]["zener_ratio"].get<double>(),
      per ? &(*per)["anisotropy"]["zener_ratio"] : nullptr, 1);
  if (j.contains("columns"))
    print_column_estimate(j["columns"]);
}
} // namespace

int run_elasticity(const ElasticityOptions& o)
{
  const auto start = std::chrono::steady_clock::now();
  json j = measure_elasticity(o); // every input checked before anything is written
  const fs::path dir =
      o.output_dir.empty()
          ? fs::path("output") / ("elasticity_" + fs::path(o.case_file).stem().string())
          : fs::path(o.output_dir);
  fs::create_directories(dir);
  j["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  verify_detail::write_json_atomically(dir, "elasticity.json", j);
  print_table(j);
  std::cout << "dembridge: wrote " << (dir / "elasticity.json").string() << std::endl;
  return 0;
}
} // namespace dembridge::app
