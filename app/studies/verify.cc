// dembridge verify: DEM specimen run vs the FE model of the same specimen (see verify.h).

#include "app/studies/verify.h"
#include "app/input/case_file.h"
#include "app/input/dem_parameters.h"
#include "app/runs/dem_run.h"
#include "app/studies/verify_report.h"
#include "dem/core/output_file.h"
#include "dem/core/types.h"
#include "dem/model/groups.h"
#include "dem/model/model.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "app/runs/fem_run.h"
#include "app/studies/verify_rows.h"
#include "coupling/specimen_fe_model.h"
#include "fem/parameters_text.h"
#endif
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deal.II/base/mpi.h>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace dembridge::app
{
namespace fs = std::filesystem;
using nlohmann::json;
using namespace verify_detail;

ElasticConstants material_from_summary(const json& j, const std::string& where)
{
  if (!j.is_object() || !j.contains("youngs_modulus") || !j["youngs_modulus"].is_number())
    throw std::runtime_error(where + ": no youngs_modulus (not the summary of a uniaxial test)");
  ElasticConstants m;
  m.youngs_modulus = j["youngs_modulus"].get<double>();
  int n = 0;
  for (const auto& [key, value] : j.items())
    if (key.rfind("poisson_ratio_", 0) == 0 && value.is_number())
    {
      m.poisson_ratio += value.get<double>();
      ++n;
    }
  if (n == 0)
    throw std::runtime_error(where + ": no poisson_ratio_* entries (not the summary of a "
                                     "uniaxial test)");
  m.poisson_ratio /= n;
  if (!(m.youngs_modulus > 0) || !std::isfinite(m.youngs_modulus))
    throw std::runtime_error(where + ": youngs_modulus " + std::to_string(m.youngs_modulus) +
                             " is not positive");
  if (!(m.poisson_ratio > -1 && m.poisson_ratio < 0.5))
    throw std::runtime_error(where + ": mean Poisson's ratio " + std::to_string(m.poisson_ratio) +
                             " is outside (-1, 0.5)");
  return m;
}

ElasticConstants material_from_tensor(const dem::Matrix6& C, const std::string& where)
{
  dem::ElasticProperties p;
  try
  {
    p = dem::elastic_properties(C, where);
  }
  catch (const dem::InputError& e)
  {
    throw std::runtime_error(e.what());
  }
  ElasticConstants m;
  m.stiffness_tensor = C;
  m.youngs_modulus = p.youngs_modulus.x();
  m.poisson_ratio = p.poisson_ratio.sum() / 6; // the six off-diagonal ratios (diagonal 0)
  return m;
}

ElasticConstants material_from_elasticity(const json& j, const std::string& where)
{
  if (!j.is_object() || !j.contains("stiffness_tensor"))
    throw std::runtime_error(where + ": no stiffness_tensor (not an elasticity.json)");
  const json& t = j["stiffness_tensor"];
  dem::Matrix6 C;
  bool ok = t.is_array() && t.size() == 6;
  for (int i = 0; ok && i < 6; ++i)
  {
    ok = t[i].is_array() && t[i].size() == 6;
    for (int k = 0; ok && k < 6; ++k)
      if ((ok = t[i][k].is_number()))
        C(i, k) = t[i][k].get<double>();
  }
  if (!ok)
    throw std::runtime_error(where + ": stiffness_tensor is not a 6x6 array of numbers");
  return material_from_tensor(C, where + ": stiffness_tensor");
}

json read_json_file(const std::string& file, const std::string& what)
{
  if (!fs::is_regular_file(file))
    throw std::runtime_error(what + " " + file + ": no such file");
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(what + " " + file + ": cannot read");
  try
  {
    return json::parse(in);
  }
  catch (const json::parse_error& e)
  {
    throw std::runtime_error(what + " " + file + ": not valid JSON (byte " +
                             std::to_string(e.byte) + ")");
  }
}

#ifdef DEMBRIDGE_HAVE_FEM
namespace
{
using coupling::SpecimenLayers;
using coupling::SpecimenTest;

/// The case and everything read from it, all checked before anything is written.
struct VerifyInputs
{
  std::unique_ptr<dealii::ParameterHandler> prm;
  std::string case_name;
  fs::path case_dir;
  dem::CaseConfig config;
  SpecimenTest test;
  std::optional<dem::Matrix6> measured_tensor; ///< --measured-tensor
  int degree = 2;
  double cell_size = 0; ///< m
};

VerifyInputs read_inputs(const VerifyOptions& o)
{
  VerifyInputs in;
  in.case_name = fs::path(o.case_file).filename().string();
  in.prm = read_case(o.case_file, o.overrides);
  auto& prm = *in.prm;
  if (prm.get("Mode") != "dem")
    throw std::runtime_error(in.case_name + ": Mode: verify needs a DEM case (Mode = dem)");
  const std::string test = prm.get({"Verification"}, "test");
  in.degree = int(prm.get_integer({"Verification"}, "degree"));
  in.cell_size = prm.get_double({"Verification"}, "cell size");
  if (prm.get_integer({"Measurements"}, "stress layers") == 0)
  {
    const long n = prm.get_integer({"Verification"}, "stress layers");
    const std::string axis = prm.get({"Verification"}, "stress layer axis");
    prm.enter_subsection("Measurements");
    prm.set("stress layers", n);
    prm.set("stress layer axis", axis);
    prm.leave_subsection();
  }
  in.case_dir = fs::absolute(o.case_file).parent_path();
  try
  {
    WorkingDirectory cd(in.case_dir);
    in.config = parse_dem_case(prm);
    const dem::Model model = dem::build_model(in.config);
    in.test = coupling::specimen_test(in.config, model, test);
    if (o.measured_tensor)
    {
      dem::ElasticityMeasurementSettings settings;
      settings.core_period =
          dem::lattice_axis_periods(in.config.particles.kind, in.config.particles.radius);
      in.measured_tensor = dem::measured_stiffness_tensor(model, settings).properties.stiffness;
    }
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(in.case_name + ": " + one_line(e.what()));
  }
  if (in.cell_size == 0)
    in.cell_size = in.test.mean_diameter;
  return in;
}

/// The FE material given on the command line, in a file or measured on the packing; none when
/// the DEM run's own uniaxial E and nu are to be used.
std::optional<ElasticConstants> given_material(const VerifyOptions& o, const VerifyInputs& in)
{
  std::optional<ElasticConstants> material;
  if (o.youngs_modulus)
  {
    const json given = {{"youngs_modulus", *o.youngs_modulus},
                        {"poisson_ratio_given", o.poisson_ratio.value_or(0.0)}};
    material = material_from_summary(given, "--youngs-modulus/--poisson-ratio");
    material->source = "command line";
  }
  else if (!o.material_from.empty())
  {
    const json j = read_json_file(o.material_from, "--material-from");
    const std::string where = "--material-from " + o.material_from;
    material = j.is_object() && j.contains("stiffness_tensor")
                   ? material_from_elasticity(j, where) // an elasticity.json
                   : material_from_summary(j, where);
    material->source = fs::absolute(o.material_from).lexically_normal().string();
  }
  else if (in.measured_tensor)
  {
    material =
        material_from_tensor(*in.measured_tensor, in.case_name + ": measured stiffness tensor");
    material->source = "measured on this case's packing (dem/measurements/elasticity_tensor.h)";
  }
  else if (in.test.test != "uniaxial")
    throw std::runtime_error(in.case_name +
                             ": verify needs E and nu for a bending test: give "
                             "--material-from UNIAXIAL_SUMMARY.json (or elasticity.json), "
                             "--measured-tensor, or --youngs-modulus and --poisson-ratio");
  if (o.shear_modulus && material && material->stiffness_tensor)
    throw std::runtime_error("--shear-modulus: the material is a full stiffness tensor already");
  if (o.shear_modulus && !(*o.shear_modulus > 0 && std::isfinite(*o.shear_modulus)))
    throw std::runtime_error("--shear-modulus: " + std::to_string(*o.shear_modulus) +
                             " is not positive");
  return material;
}

/// The summary of a finished DEM run of the case (--dem-run), checked to be one.
json finished_dem_run(const std::string& folder, const SpecimenTest& t)
{
  json dem = read_json_file((fs::path(folder) / "summary.json").string(), "--dem-run");
  std::string mismatch;
  if (dem.value("mode", "") != "dem" || dem.value("n_particles", 0ul) != t.n_particles)
    mismatch = "mode dem and " + std::to_string(t.n_particles) + " particles expected";
  for (const auto& g : t.mapped_groups)
    if (mismatch.empty() && !(dem.contains("groups") && dem["groups"].contains(g)))
      mismatch = "no group '" + g + "'";
  if (!mismatch.empty())
    throw std::runtime_error("--dem-run " + folder + ": summary.json is not a run of this case (" +
                             mismatch + ")");
  return dem;
}

json run_dem(const VerifyInputs& in, const fs::path& dir)
{
  const fs::path dem_dir = fs::absolute(dir / "dem");
  fs::create_directories(dem_dir);
  fs::remove(dem_dir / "summary.json");
  std::printf("verify: step 1 of 2, the DEM run of %s (into %s)\n", in.case_name.c_str(),
              dem_dir.c_str());
  std::fflush(stdout);
  json dem;
  try
  {
    WorkingDirectory cd(in.case_dir);
    dem = run_dem_case(*in.prm, dem_dir);
  }
  catch (const dem::InputError& e)
  {
    throw std::runtime_error(in.case_name + ": " + e.what());
  }
  dem["case"] = in.case_name;
  write_json_atomically(dem_dir, "summary.json", dem);
  return dem;
}

coupling::SpecimenMaterial fe_material(const ElasticConstants& m)
{
  return {m.youngs_modulus, m.poisson_ratio, m.shear_modulus, m.stiffness_tensor};
}

/// The FE model of the specimen: its case file (what ran, rerunnable) and its run.
json run_fe(const VerifyInputs& in, const ElasticConstants& material, const json& dem,
            const SpecimenLayers& layers, const fs::path& dir)
{
  const fem::Parameters parameters = coupling::specimen_fe_parameters(
      in.test, fe_material(material), dem, in.degree, in.cell_size, layers);
  const fs::path fe_dir = fs::absolute(dir / "fem");
  fs::create_directories(fe_dir);
  fs::remove(fe_dir / "summary.json");
  {
    dem::OutputFile out(fe_dir / "case.prm"); // failures name the file and the reason
    out << fem::case_file_text(parameters, {"Derived by `dembridge verify` from the DEM case " +
                                            in.case_name + "; runnable with `dembridge run`."});
    out.close();
  }
  std::printf("verify: step 2 of 2, the FE model of the specimen (E = %.6g Pa, nu = %.4g; into "
              "%s)\n",
              material.youngs_modulus, material.poisson_ratio, fe_dir.c_str());
  std::fflush(stdout);
  json fe = run_fem_case(parameters, fe_dir, MPI_COMM_WORLD);
  fe["case"] = "case.prm";
  write_json_atomically(fe_dir, "summary.json", fe);
  return fe;
}

std::string constants_text(const ElasticConstants& material)
{
  char constants[128];
  if (material.stiffness_tensor)
  {
    const dem::Matrix6& C = *material.stiffness_tensor;
    std::snprintf(constants, sizeof constants,
                  "stiffness tensor C11 = %.4g, C12 = %.4g, C44 = %.4g GPa", C(0, 0) / 1e9,
                  C(0, 1) / 1e9, C(3, 3) / 1e9);
  }
  else
    std::snprintf(constants, sizeof constants, "E = %.6g GPa, nu = %.4g%s",
                  material.youngs_modulus / 1e9, material.poisson_ratio,
                  material.shear_modulus > 0 ? ", cubic" : "");
  if (material.shear_modulus > 0)
    std::snprintf(constants + std::strlen(constants), sizeof constants - std::strlen(constants),
                  " G = %.4g GPa", material.shear_modulus / 1e9);
  return constants;
}

json material_json(const ElasticConstants& material)
{
  json m = {
      {"youngs_modulus", material.youngs_modulus},
      {"poisson_ratio", material.poisson_ratio},
      {"shear_modulus", material.shear_modulus > 0 ? json(material.shear_modulus) : json(nullptr)},
      {"symmetry", material.stiffness_tensor    ? "anisotropic (6x6 tensor)"
                   : material.shear_modulus > 0 ? "cubic"
                                                : "isotropic"},
      {"source", material.source}};
  if (material.stiffness_tensor)
  {
    json rows = json::array();
    for (int i = 0; i < 6; ++i)
    {
      json row = json::array();
      for (int k = 0; k < 6; ++k)
        row.push_back((*material.stiffness_tensor)(i, k));
      rows.push_back(row);
    }
    m["stiffness_tensor"] = rows;
  }
  return m;
}

json stress_layers_json(const Report& report)
{
  json layer_rows = json::array();
  double max_dem = 0, max_diff = 0;
  bool complete = true;
  for (const auto& row : report.layers)
  {
    layer_rows.push_back(row_json(row));
    complete = complete && row.dem && row.fem;
    if (row.dem && row.fem)
    {
      max_dem = std::max(max_dem, std::abs(*row.dem));
      max_diff = std::max(max_diff, std::abs(*row.fem - *row.dem));
    }
  }
  json layers = {{"axis", report.layer_axis},
                 {"component", report.layer_component},
                 {"edges", report.layer_edges},
                 {"rows", layer_rows},
                 {"max_abs_difference", complete ? json(max_diff) : json(nullptr)},
                 {"max_difference_relative_to_max_dem",
                  complete && max_dem > 0 ? json(max_diff / max_dem) : json(nullptr)}};
  if (!complete)
    layers["note"] = "the DEM summary has no stress_layers";
  return layers;
}

json verification_summary(const VerifyOptions& o, const VerifyInputs& in,
                          const ElasticConstants& material, const json& fe, const Report& report)
{
  const SpecimenTest& t = in.test;
  json summary;
  summary["case"] = in.case_name;
  summary["test"] = t.test;
  summary["material"] = material_json(material);
  summary["fe_model"] = {{"degree", in.degree},
                         {"cell_size", in.cell_size},
                         {"n_dofs", fe.value("n_dofs", 0)},
                         {"box_lower", {t.body_lo.x(), t.body_lo.y(), t.body_lo.z()}},
                         {"box_upper", {t.body_hi.x(), t.body_hi.y(), t.body_hi.z()}},
                         {"case", "fem/case.prm"}};
  summary["specimen_extent"] = {{"lower", {t.lo.x(), t.lo.y(), t.lo.z()}},
                                {"upper", {t.hi.x(), t.hi.y(), t.hi.z()}}};
  summary["dem_run"] = o.dem_run.empty() ? std::string("dem") : o.dem_run;
  summary["groups_not_mapped"] = t.ignored_groups;
  for (const auto& row : report.scalars)
    summary["quantities"][row.key] = row_json(row);
  summary["stress_layers"] = stress_layers_json(report);
  return summary;
}

void print_report(const std::string& title, const Report& report, const json& summary,
                  const fs::path& dir)
{
  std::cout << "\n" << title << "\n";
  std::printf("%-34s %15s %15s %11s\n", "quantity", "DEM", "FE", "rel. diff");
  for (const auto& rows : {&report.scalars, &report.layers})
    for (const auto& row : *rows)
    {
      const json j = row_json(row);
      auto cell = [&](const char* k, const char* format)
      {
        char text[32] = "-";
        if (j[k].is_number())
          std::snprintf(text, sizeof text, format, j[k].get<double>());
        return std::string(text);
      };
      std::printf("%-34s %15s %15s %11s\n", row.key.c_str(), cell("dem", "%.8g").c_str(),
                  cell("fem", "%.8g").c_str(), cell("relative_difference", "%+.2e").c_str());
    }
  if (summary["plot"]["file"].is_null())
    std::cerr << "dembridge verify: warning: comparison.png not written: "
              << summary["plot"]["error"].get<std::string>() << std::endl;
  std::cout << "dembridge: wrote " << (dir / "summary.json").string() << ", comparison.csv"
            << (summary["plot"]["file"].is_null() ? "" : ", comparison.png") << std::endl;
}
} // namespace

int verify(const VerifyOptions& o)
{
  // 1. Inputs, all checked before anything is written.
  const VerifyInputs in = read_inputs(o);
  std::optional<ElasticConstants> material = given_material(o, in);
  json dem;
  if (!o.dem_run.empty())
    dem = finished_dem_run(o.dem_run, in.test);

  // 2. Output folder: stale results go first.
  const fs::path dir =
      o.output_dir.empty()
          ? fs::path("output") / ("verify_" + fs::path(o.case_file).stem().string())
          : fs::path(o.output_dir);
  fs::create_directories(dir);
  for (const char* f : {"summary.json", "comparison.csv", "comparison.png"})
    fs::remove(dir / f);

  // 3. The DEM run, and its uniaxial E and nu as the FE material when none was given.
  if (o.dem_run.empty())
    dem = run_dem(in, dir);
  if (!material)
  {
    json measured = dem;
    if (const auto e = dem_youngs_modulus(in.test, dem))
      measured["youngs_modulus"] = *e;
    material =
        material_from_summary(measured, "DEM summary (uniaxial run of " + in.case_name + ")");
    material->source = "this DEM run";
  }
  if (o.shear_modulus)
    material->shear_modulus = *o.shear_modulus;

  // 4. The FE run.
  const int n_layers = int(in.prm->get_integer({"Measurements"}, "stress layers"));
  const int layer_axis = in.prm->get({"Measurements"}, "stress layer axis")[0] - 'x';
  const SpecimenLayers layers = coupling::specimen_layers(dem, in.test, n_layers, layer_axis);
  const json fe = run_fe(in, *material, dem, layers, dir);

  // 5. The report.
  const Report report = compare_results(in.test, dem, fe, layers);
  const std::string title =
      in.case_name + " (" + in.test.test + "): DEM vs FE, " + constants_text(*material);
  json summary = verification_summary(o, in, *material, fe, report);
  summary["plot"] = write_table_and_plot(report, dir, title, o.plot);
  write_json_atomically(dir, "summary.json", summary);
  print_report(title, report, summary, dir);
  return 0;
}
#else
int verify(const VerifyOptions&)
{
  throw std::runtime_error("verify: this build has no FEM layer (deal.II not found)");
}
#endif
} // namespace dembridge::app
