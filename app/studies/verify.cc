// dembridge verify: DEM specimen run vs the FE model of the same specimen (see verify.h).

#include "app/studies/verify.h"
#include "app/input/case_file.h"
#include "app/input/dem_parameters.h"
#include "app/runs/dem_run.h"
#include "app/studies/verify_model.h"
#include "app/studies/verify_report.h"
#include "dem/core/output_file.h"
#include "dem/core/types.h"
#include "dem/model/groups.h"
#include "dem/model/model.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "fem/fem_case.h"
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

void declare_verification_parameters(dealii::ParameterHandler& prm)
{
  namespace P = dealii::Patterns;
  prm.enter_subsection("Verification");
  prm.declare_entry("test", "auto", P::Selection("auto|uniaxial|bending"),
                    "Which DEM test `dembridge verify` models: uniaxial (Measurements/modulus "
                    "groups), bending (Measurements/flexural groups), auto: the one the case "
                    "measures.");
  prm.declare_entry("degree", "2", P::Integer(1, 2), "FE degree of the verification model.");
  prm.declare_entry("cell size", "0", P::Double(0),
                    "FE cell size (m) of the verification model; 0: the mean particle diameter.");
  prm.declare_entry("stress layers", "10", P::Integer(1, 1000),
                    "Slabs for the layer-averaged stress when the case sets no Measurements/"
                    "stress layers.");
  prm.declare_entry("stress layer axis", "z", P::Selection("x|y|z"),
                    "Normal of those slabs (through the depth: z).");
  prm.leave_subsection();
}

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

namespace
{
const char* const axis_name = "xyz";

std::optional<double> number_at(const json& j, std::initializer_list<const char*> path)
{
  const json* node = &j;
  for (const char* key : path)
  {
    if (!node->is_object() || !node->contains(key))
      return std::nullopt;
    node = &(*node)[key];
  }
  return node->is_number() ? std::optional<double>(node->get<double>()) : std::nullopt;
}

std::optional<double> component(const json& j, std::initializer_list<const char*> path, int d)
{
  const json* node = &j;
  for (const char* key : path)
  {
    if (!node->is_object() || !node->contains(key))
      return std::nullopt;
    node = &(*node)[key];
  }
  return node->is_array() && node->size() == 3 ? std::optional<double>((*node)[d].get<double>())
                                               : std::nullopt;
}

std::optional<double> dem_strain_energy(const json& dem)
{
  if (auto e = number_at(dem, {"strain_energy"}))
    return e;
  return number_at(dem, {"energy", "strain"});
}

/// The DEM's Young's modulus (thesis eq. 64). Under force control the DEM summary's
/// youngs_modulus reads the loaded end's net force (zero in equilibrium), so there E comes from
/// the fixed end's reaction: E = -R_fixed / A * L0 / (u_loaded - u_fixed), as in the FE summary.
std::optional<double> dem_youngs_modulus(const Plan& p, const json& dem)
{
  if (p.displacement_control)
    return number_at(dem, {"youngs_modulus"});
  const int a = p.axis;
  const auto r = component(dem, {"groups", p.fixed_group.c_str(), "force"}, a);
  const auto ul = component(dem, {"groups", p.loaded_group.c_str(), "mean_displacement"}, a);
  const auto uf = component(dem, {"groups", p.fixed_group.c_str(), "mean_displacement"}, a);
  const auto area = number_at(dem, {"cross_section_area"});
  const auto length = number_at(dem, {"gauge_length"});
  if (!r || !ul || !uf || !area || !length || *ul == *uf || *area <= 0)
    return std::nullopt;
  return -*r / *area * *length / (*ul - *uf);
}

Report compare(const Plan& p, const json& dem, const json& fe, const Layers& layers)
{
  Report r;
  const std::string a(1, axis_name[p.axis]);
  if (p.test == "uniaxial")
  {
    const int d = p.axis;
    const char* f = p.fixed_group.c_str();
    const char* l = p.loaded_group.c_str();
    r.scalars.push_back(
        {"youngs_modulus",
         "Pa",
         dem_youngs_modulus(p, dem),
         number_at(fe, {"youngs_modulus"}),
         {},
         p.displacement_control ? "thesis eq. 64" : "thesis eq. 64, from the fixed-end reaction"});
    r.scalars.push_back({"reaction_" + p.fixed_group + "_" + a,
                         "N",
                         component(dem, {"groups", f, "force"}, d),
                         component(fe, {"reactions", p.fixed_face.c_str()}, d),
                         {},
                         "support on the specimen"});
    if (p.displacement_control)
      r.scalars.push_back({"reaction_" + p.loaded_group + "_" + a,
                           "N",
                           component(dem, {"groups", l, "force"}, d),
                           component(fe, {"reactions", p.loaded_face.c_str()}, d),
                           {},
                           "grip on the specimen"});
    std::optional<double> du;
    if (auto ul = component(dem, {"groups", l, "mean_displacement"}, d))
      if (auto uf = component(dem, {"groups", f, "mean_displacement"}, d))
        du = *ul - *uf;
    r.scalars.push_back({"end_displacement",
                         "m",
                         du,
                         number_at(fe, {"elongation"}),
                         {},
                         "loaded minus fixed end along " + a});
  }
  else
  {
    auto fe_top = component(fe, {"mean_displacements", "top"}, 2);
    auto fe_bottom = component(fe, {"mean_displacements", "bottom"}, 2);
    std::optional<double> fe_mean, fe_load, dem_top;
    if (fe_top && fe_bottom)
      fe_mean = 0.5 * (std::abs(*fe_top) + std::abs(*fe_bottom));
    const auto dem_mean = number_at(dem, {"midspan_deflection"});
    const auto dem_bottom = number_at(dem, {"bottom_deflection"});
    if (dem_mean && dem_bottom)
      dem_top = 2 * *dem_mean - *dem_bottom;
    auto fe_pin = component(fe, {"reactions", p.pin.c_str()}, 2);
    auto fe_roller = component(fe, {"reactions", p.roller.c_str()}, 2);
    if (fe_pin && fe_roller)
      fe_load = std::abs(*fe_pin + *fe_roller);
    r.scalars.push_back(
        {"midspan_deflection", "m", dem_mean, fe_mean, {}, "mean of top and bottom midspan"});
    r.scalars.push_back({"top_deflection",
                         "m",
                         dem_top,
                         fe_top ? std::optional<double>(std::abs(*fe_top)) : std::nullopt,
                         {},
                         "under the load"});
    r.scalars.push_back({"bottom_deflection",
                         "m",
                         dem_bottom,
                         fe_bottom ? std::optional<double>(std::abs(*fe_bottom)) : std::nullopt,
                         {},
                         "bottom midspan"});
    r.scalars.push_back({"flexural_load",
                         "N",
                         number_at(dem, {"flexural_load"}),
                         fe_load,
                         {},
                         "sum of the support reactions"});
    r.scalars.push_back({"reaction_" + p.pin + "_z",
                         "N",
                         component(dem, {"groups", p.pin.c_str(), "force"}, 2),
                         fe_pin,
                         {},
                         ""});
    r.scalars.push_back({"reaction_" + p.roller + "_z",
                         "N",
                         component(dem, {"groups", p.roller.c_str(), "force"}, 2),
                         fe_roller,
                         {},
                         ""});
    // eq. 69 with the FE deflection and load (same span, load length, section, nu)
    std::optional<double> fe_modulus;
    const auto dem_modulus = number_at(dem, {"flexural_modulus"});
    const auto dem_load = number_at(dem, {"flexural_load"});
    if (dem_modulus && dem_mean && dem_load && fe_mean && fe_load && *fe_mean > 0 && *dem_load > 0)
      fe_modulus = *dem_modulus * (*fe_load / *dem_load) * (*dem_mean / *fe_mean);
    r.scalars.push_back({"flexural_modulus", "Pa", dem_modulus, fe_modulus, {}, "thesis eq. 69"});
  }
  r.scalars.push_back(
      {"strain_energy", "J", dem_strain_energy(dem), number_at(fe, {"strain_energy"}), {}, ""});

  // Layers: the normal stress along the test axis; FE integrals over the DEM slab volumes.
  r.layer_axis = std::string(1, axis_name[layers.axis]);
  r.layer_component = "sigma_" + a + a;
  r.layer_edges = layers.edges;
  double section = 1;
  for (int d = 0; d < 3; ++d)
    if (d != layers.axis)
      section *= p.hi[d] - p.lo[d];
  const json* dem_sigma = dem.contains("stress_layers") ? &dem["stress_layers"]["sigma"] : nullptr;
  const auto& fe_layers = fe.at("stress_layers");
  for (std::size_t k = 0; k + 1 < layers.edges.size(); ++k)
  {
    const double thickness = layers.edges[k + 1] - layers.edges[k];
    Row row{"layer_" + std::to_string(k) + "_" + r.layer_component, "Pa", {}, {},
            0.5 * (layers.edges[k] + layers.edges[k + 1]),          ""};
    if (dem_sigma && k < dem_sigma->size())
      row.dem = (*dem_sigma)[k][p.axis][p.axis].get<double>();
    row.fem = fe_layers["sigma"][k][p.axis][p.axis].get<double>() *
              fe_layers["volume"][k].get<double>() / (thickness * section);
    r.layers.push_back(row);
  }
  return r;
}
} // namespace

int verify(const VerifyOptions& o)
{
#ifndef DEMBRIDGE_HAVE_FEM
  (void)o;
  throw std::runtime_error("verify: this build has no FEM layer (deal.II not found)");
#else
  const std::string case_name = fs::path(o.case_file).filename().string();
  auto in_case = [&](const std::string& msg) { return case_name + ": " + msg; };

  // ---- 1. Inputs, all checked before anything is written.
  auto prm = read_case(o.case_file, o.overrides);
  if (prm->get("Mode") != "dem")
    throw std::runtime_error(in_case("Mode: verify needs a DEM case (Mode = dem)"));
  const std::string test = prm->get({"Verification"}, "test");
  const int degree = int(prm->get_integer({"Verification"}, "degree"));
  double cell_size = prm->get_double({"Verification"}, "cell size");
  if (prm->get_integer({"Measurements"}, "stress layers") == 0)
  {
    const long n = prm->get_integer({"Verification"}, "stress layers");
    const std::string axis = prm->get({"Verification"}, "stress layer axis");
    prm->enter_subsection("Measurements");
    prm->set("stress layers", n);
    prm->set("stress layer axis", axis);
    prm->leave_subsection();
  }
  const fs::path case_dir = fs::absolute(o.case_file).parent_path();
  dem::CaseConfig config;
  Plan plan;
  std::optional<dem::Matrix6> measured_tensor; // --measured-tensor
  try
  {
    WorkingDirectory cd(case_dir);
    config = parse_dem_case(*prm);
    const dem::Model model = dem::build_model(config);
    plan = make_plan(config, model, test);
    if (o.measured_tensor)
    {
      dem::ElasticityMeasurementSettings settings;
      settings.core_period =
          dem::lattice_axis_periods(config.particles.kind, config.particles.radius);
      measured_tensor = dem::measured_stiffness_tensor(model, settings).properties.stiffness;
    }
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(in_case(one_line(e.what())));
  }
  if (cell_size == 0)
    cell_size = plan.mean_diameter;

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
  else if (measured_tensor)
  {
    material = material_from_tensor(*measured_tensor, in_case("measured stiffness tensor"));
    material->source = "measured on this case's packing (dem/measurements/elasticity_tensor.h)";
  }
  else if (plan.test != "uniaxial")
    throw std::runtime_error(in_case("verify needs E and nu for a bending test: give "
                                     "--material-from UNIAXIAL_SUMMARY.json (or elasticity.json), "
                                     "--measured-tensor, or --youngs-modulus and --poisson-ratio"));
  if (o.shear_modulus && material && material->stiffness_tensor)
    throw std::runtime_error("--shear-modulus: the material is a full stiffness tensor already");
  if (o.shear_modulus && !(*o.shear_modulus > 0 && std::isfinite(*o.shear_modulus)))
    throw std::runtime_error("--shear-modulus: " + std::to_string(*o.shear_modulus) +
                             " is not positive");
  json dem;
  if (!o.dem_run.empty())
  {
    dem = read_json_file((fs::path(o.dem_run) / "summary.json").string(), "--dem-run");
    std::string mismatch;
    if (dem.value("mode", "") != "dem" || dem.value("n_particles", 0ul) != plan.n_particles)
      mismatch = "mode dem and " + std::to_string(plan.n_particles) + " particles expected";
    for (const auto& g : plan.mapped_groups)
      if (mismatch.empty() && !(dem.contains("groups") && dem["groups"].contains(g)))
        mismatch = "no group '" + g + "'";
    if (!mismatch.empty())
      throw std::runtime_error("--dem-run " + o.dem_run +
                               ": summary.json is not a run of this case (" + mismatch + ")");
  }

  // ---- 2. Output folder: stale results go first.
  const fs::path dir =
      o.output_dir.empty()
          ? fs::path("output") / ("verify_" + fs::path(o.case_file).stem().string())
          : fs::path(o.output_dir);
  fs::create_directories(dir);
  for (const char* f : {"summary.json", "comparison.csv", "comparison.png"})
    fs::remove(dir / f);

  // ---- 3. DEM run.
  if (o.dem_run.empty())
  {
    const fs::path dem_dir = fs::absolute(dir / "dem");
    fs::create_directories(dem_dir);
    fs::remove(dem_dir / "summary.json");
    std::printf("verify: step 1 of 2, the DEM run of %s (into %s)\n", case_name.c_str(),
                dem_dir.c_str());
    std::fflush(stdout);
    try
    {
      WorkingDirectory cd(case_dir);
      dem = run_dem_case(*prm, dem_dir);
    }
    catch (const dem::InputError& e)
    {
      throw std::runtime_error(in_case(e.what()));
    }
    dem["case"] = case_name;
    write_json_atomically(dem_dir, "summary.json", dem);
  }
  if (!material)
  {
    json measured = dem;
    if (const auto e = dem_youngs_modulus(plan, dem))
      measured["youngs_modulus"] = *e;
    material = material_from_summary(measured, "DEM summary (uniaxial run of " + case_name + ")");
    material->source = "this DEM run";
  }

  if (o.shear_modulus)
    material->shear_modulus = *o.shear_modulus;

  // ---- 4. FE run.
  const int n_layers = int(prm->get_integer({"Measurements"}, "stress layers"));
  const int layer_axis = prm->get({"Measurements"}, "stress layer axis")[0] - 'x';
  const Layers layers = layers_from(dem, plan, n_layers, layer_axis);
  const fs::path fe_dir = fs::absolute(dir / "fem");
  fs::create_directories(fe_dir);
  fs::remove(fe_dir / "summary.json");
  {
    dem::OutputFile out(fe_dir / "case.prm"); // failures name the file and the reason
    out << fe_case(plan, *material, dem, degree, cell_size, layers);
    out.close();
  }
  json fe;
  {
    auto fe_prm = read_case((fe_dir / "case.prm").string(), {});
    std::printf("verify: step 2 of 2, the FE model of the specimen (E = %.6g Pa, nu = %.4g; into "
                "%s)\n",
                material->youngs_modulus, material->poisson_ratio, fe_dir.c_str());
    std::fflush(stdout);
    fe = fem::run_case(*fe_prm, fe_dir, MPI_COMM_WORLD);
    fe["case"] = "case.prm";
    write_json_atomically(fe_dir, "summary.json", fe);
  }

  // ---- 5. Report.
  const Report report = compare(plan, dem, fe, layers);
  char constants[128];
  if (material->stiffness_tensor)
  {
    const dem::Matrix6& C = *material->stiffness_tensor;
    std::snprintf(constants, sizeof constants,
                  "stiffness tensor C11 = %.4g, C12 = %.4g, C44 = %.4g GPa", C(0, 0) / 1e9,
                  C(0, 1) / 1e9, C(3, 3) / 1e9);
  }
  else
    std::snprintf(constants, sizeof constants, "E = %.6g GPa, nu = %.4g%s",
                  material->youngs_modulus / 1e9, material->poisson_ratio,
                  material->shear_modulus > 0 ? ", cubic" : "");
  if (material->shear_modulus > 0)
    std::snprintf(constants + std::strlen(constants), sizeof constants - std::strlen(constants),
                  " G = %.4g GPa", material->shear_modulus / 1e9);
  const std::string title = case_name + " (" + plan.test + "): DEM vs FE, " + constants;
  json summary;
  summary["case"] = case_name;
  summary["test"] = plan.test;
  summary["material"] = {{"youngs_modulus", material->youngs_modulus},
                         {"poisson_ratio", material->poisson_ratio},
                         {"shear_modulus", material->shear_modulus > 0
                                               ? json(material->shear_modulus)
                                               : json(nullptr)},
                         {"symmetry", material->stiffness_tensor    ? "anisotropic (6x6 tensor)"
                                      : material->shear_modulus > 0 ? "cubic"
                                                                    : "isotropic"},
                         {"source", material->source}};
  if (material->stiffness_tensor)
  {
    json rows = json::array();
    for (int i = 0; i < 6; ++i)
    {
      json row = json::array();
      for (int k = 0; k < 6; ++k)
        row.push_back((*material->stiffness_tensor)(i, k));
      rows.push_back(row);
    }
    summary["material"]["stiffness_tensor"] = rows;
  }
  summary["fe_model"] = {{"degree", degree},
                         {"cell_size", cell_size},
                         {"n_dofs", fe.value("n_dofs", 0)},
                         {"box_lower", {plan.body_lo.x(), plan.body_lo.y(), plan.body_lo.z()}},
                         {"box_upper", {plan.body_hi.x(), plan.body_hi.y(), plan.body_hi.z()}},
                         {"case", "fem/case.prm"}};
  summary["specimen_extent"] = {{"lower", {plan.lo.x(), plan.lo.y(), plan.lo.z()}},
                                {"upper", {plan.hi.x(), plan.hi.y(), plan.hi.z()}}};
  summary["dem_run"] = o.dem_run.empty() ? std::string("dem") : o.dem_run;
  summary["groups_not_mapped"] = plan.ignored_groups;
  for (const auto& row : report.scalars)
    summary["quantities"][row.key] = row_json(row);
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
  summary["stress_layers"] = {{"axis", report.layer_axis},
                              {"component", report.layer_component},
                              {"edges", report.layer_edges},
                              {"rows", layer_rows},
                              {"max_abs_difference", complete ? json(max_diff) : json(nullptr)},
                              {"max_difference_relative_to_max_dem",
                               complete && max_dem > 0 ? json(max_diff / max_dem) : json(nullptr)}};
  if (!complete)
    summary["stress_layers"]["note"] = "the DEM summary has no stress_layers";
  summary["plot"] = write_table_and_plot(report, dir, title, o.plot);
  write_json_atomically(dir, "summary.json", summary);

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
  return 0;
#endif
}
} // namespace dembridge::app
