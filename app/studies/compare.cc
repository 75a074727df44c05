// dembridge compare: coupled against full DEM and full FE (see compare.h).
#include "app/studies/compare.h"
#include "app/input/case_file.h"
#include "app/input/coupled_parameters.h"
#include "app/input/dem_parameters.h"
#include "app/job/provenance.h"
#include "app/runs/fem_run.h"
#include "app/runs/memory_guard.h"
#include "app/studies/compare_cases.h"
#include "app/studies/compare_plot.h"
#include "app/studies/compare_process.h"
#include "app/studies/verify.h"
#include "app/studies/verify_report.h"
#include "coupling/fixed_region.h"
#include "coupling/full_models.h"
#include "dem/core/output_file.h"
#include "dem/measurements/failure_measurements.h"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

namespace dembridge::app
{
namespace fs = std::filesystem;
using json = nlohmann::json;
using dem::Vec3;
using verify_detail::num;
using verify_detail::python;
using verify_detail::write_json_atomically;

namespace
{
struct Table
{
  std::map<std::string, std::size_t> column;
  std::vector<std::vector<double>> rows;
  std::vector<double> get(const std::string& name, const std::string& file) const
  {
    const auto it = column.find(name);
    if (it == column.end())
      throw std::runtime_error("compare: " + file + " has no column '" + name + "'");
    std::vector<double> v;
    for (const auto& r : rows)
      v.push_back(it->second < r.size() ? r[it->second] : std::nan(""));
    return v;
  }
};

Table read_csv(const fs::path& file)
{
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error("compare: cannot read " + file.string());
  Table t;
  std::string line;
  std::getline(in, line);
  {
    std::istringstream h(line);
    std::string name;
    for (std::size_t k = 0; std::getline(h, name, ','); ++k)
      t.column[name] = k;
  }
  while (std::getline(in, line))
  {
    std::istringstream r(line);
    std::string cell;
    std::vector<double> row;
    while (std::getline(r, cell, ','))
    {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      row.push_back(end != cell.c_str() ? v : std::nan(""));
    }
    t.rows.push_back(row);
  }
  return t;
}

struct Curve
{
  std::vector<double> deflection, load;
};

/// Peak |load| and the limit load (dem/measurements/failure_measurements.h), the deflections
/// there, and the initial stiffness: least squares through the origin over the records below
/// half the peak, before the first broken bond.
json curve_figures(const Curve& c, const std::vector<double>& broken)
{
  json j;
  if (c.load.empty())
    return j;
  const dem::PeakLoad peak = dem::peak_of(c.load, c.deflection);
  const dem::PeakLoad limit = dem::limit_of(c.load, c.deflection);
  j["peak_load"] = std::abs(peak.load);
  j["deflection_at_peak"] = std::abs(peak.displacement);
  j["limit_load"] = std::abs(limit.load);
  j["deflection_at_limit"] = std::abs(limit.displacement);
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < c.load.size(); ++k)
  {
    if (std::abs(c.load[k]) > 0.5 * std::abs(peak.load) || (k < broken.size() && broken[k] > 0))
      break;
    sxy += c.deflection[k] * c.load[k];
    sxx += c.deflection[k] * c.deflection[k];
  }
  if (sxx > 0)
    j["initial_stiffness"] = sxy / sxx;
  return j;
}

double distance_to_box(const Vec3& x, const Vec3& lo, const Vec3& hi)
{
  return (x - x.cwiseMax(lo).cwiseMin(hi)).norm();
}

std::optional<Vec3> first_crack(const fs::path& cracks)
{
  if (!fs::exists(cracks))
    return std::nullopt;
  const Table t = read_csv(cracks);
  if (t.rows.empty())
    return std::nullopt;
  const auto& r = t.rows.front();
  return Vec3(r[t.column.at("x")], r[t.column.at("y")], r[t.column.at("z")]);
}

json to_json(const Vec3& v)
{
  return {v.x(), v.y(), v.z()};
}

} // namespace

CLI::App* add_compare_command(CLI::App& app, CompareOptions& o)
{
  auto* cmd = app.add_subcommand(
      "compare", "Run a coupled case, its full-DEM and its full (elastic) FE counterpart; "
                 "compare load-deflection, peak, fracture energy, cracks, time and memory");
  cmd->add_option("case", o.case_file, "Coupled case file (Mode = coupled)")->required();
  cmd->add_option("--set", o.overrides, "Override a parameter: \"Section/Key=value\"");
  cmd->add_option("--output-dir", o.output_dir, "Output folder (default output/compare_CASE)");
  cmd->add_option("--fe-cell-size", o.fe_cell_size,
                  "Cell size (m) of the FE reference (default: two particle diameters)");
  cmd->add_option("--fe-degree", o.fe_degree, "FE_Q degree of the FE reference (1 or 2)")
      ->check(CLI::Range(1, 2));
  cmd->add_flag("!--no-plot", o.plot, "Do not write comparison.png");
  return cmd;
}

namespace
{
/// The load-deflection curve of a coupled run (its own measure: load_displacement, load).
Curve coupled_curve(const Table& h, const std::string& file)
{
  return {h.get("load_displacement", file), h.get("load", file)};
}

/// The full-DEM curve: the loaded group's displacement and force along the push.
Curve dem_curve_of(const Table& h, const std::string& g, const Vec3& direction,
                   const std::string& file)
{
  Curve c;
  std::vector<double> u[3], F[3];
  for (int d = 0; d < 3; ++d)
  {
    u[d] = h.get(g + "_u" + std::string(1, "xyz"[d]), file);
    F[d] = h.get(g + "_f" + std::string(1, "xyz"[d]), file);
  }
  for (std::size_t k = 0; k < h.rows.size(); ++k)
  {
    c.deflection.push_back(u[0][k] * direction.x() + u[1][k] * direction.y() +
                           u[2][k] * direction.z());
    c.load.push_back(F[0][k] * direction.x() + F[1][k] * direction.y() + F[2][k] * direction.z());
  }
  return c;
}

/// Model a against model b: the ratios of their figures, the speed-up (b's wall time over a's)
/// and the distance between their first cracks.
json versus(const json& a, const json& b)
{
  json vs;
  auto ratio = [&](const char* key) -> json
  {
    if (!a.contains(key) || !b.contains(key) || b[key].get<double>() == 0)
      return nullptr;
    return a[key].get<double>() / b[key].get<double>();
  };
  for (const char* key : {"peak_load", "deflection_at_peak", "limit_load", "deflection_at_limit",
                          "fracture_energy", "n_broken_bonds", "initial_stiffness"})
    vs[std::string(key) + "_ratio"] = ratio(key);
  vs["peak_memory_ratio"] = ratio("peak_memory_bytes");
  vs["speedup"] = a["wall_seconds"].get<double>() > 0
                      ? json(b["wall_seconds"].get<double>() / a["wall_seconds"].get<double>())
                      : json(nullptr);
  if (a.contains("first_crack") && b.contains("first_crack"))
  {
    const Vec3 x(a["first_crack"][0].get<double>(), a["first_crack"][1].get<double>(),
                 a["first_crack"][2].get<double>());
    const Vec3 y(b["first_crack"][0].get<double>(), b["first_crack"][1].get<double>(),
                 b["first_crack"][2].get<double>());
    vs["first_crack_distance"] = (x - y).norm();
  }
  return vs;
}

/// What an adaptive run's summary says of its region's growth.
void add_growth_figures(json& model, const json& summary)
{
  for (const char* key : {"n_region_growth_events", "n_particles_final", "growth_energy_jump_max",
                          "particle_region_packing_fraction", "region_cells_final",
                          "max_utilisation", "region_growth_capped"})
    if (summary.contains(key))
      model[key] = summary[key];
}

struct ModelCurves
{
  std::vector<std::pair<std::string, Curve>> curves; ///< coupled, [coupled_fixed,] full_dem
  double fe_stiffness = 0;
};

void write_curves(const fs::path& dir, const ModelCurves& m)
{
  const fs::path part = dir / "comparison.csv.part";
  dem::OutputFile out(part); // failures name the file and the reason
  out << "model,deflection,load\n" << std::setprecision(10);
  for (const auto& [name, c] : m.curves)
    for (std::size_t k = 0; k < c.load.size(); ++k)
      out << name << ',' << c.deflection[k] << ',' << c.load[k] << '\n';
  double top = 0, most = 0; // the elastic line up to a quarter above the coupled run's largest load
  const Curve& coupled = m.curves.front().second;
  for (std::size_t k = 0; k < coupled.load.size(); ++k)
    top = std::max(top, coupled.deflection[k]), most = std::max(most, coupled.load[k]);
  if (m.fe_stiffness > 0 && most > 0)
    top = std::min(top, 1.25 * most / m.fe_stiffness);
  out << "full_fem,0,0\nfull_fem," << top << ',' << m.fe_stiffness * top << '\n';
  out.close();
  fs::rename(part, dir / "comparison.csv");
}

/// comparison.png through the plot script (compare_plot.h); the runs' crack files by model.
/// Returns whether it was written.
bool write_plot(const fs::path& dir, const std::string& title, const Vec3& direction,
                const coupling::FullDemLayout& layout, const std::vector<std::string>& crack_models)
{
  // the side view: the span axis against the load axis
  int v = 2;
  for (int d = 0; d < 3; ++d)
    if (std::abs(direction[d]) > std::abs(direction[v]))
      v = d;
  const Vec3 extent = layout.box_size;
  int h = v == 0 ? 1 : 0;
  for (int d = 0; d < 3; ++d)
    if (d != v && extent[d] > extent[h])
      h = d;
  const fs::path script = dir / "comparison_plot.py", log = dir / "comparison_plot.log";
  const fs::path png = dir / "comparison.part.png";
  {
    std::ofstream out(script);
    out << "# Written by `dembridge compare`\n" << compare_plot_script;
  }
  std::vector<std::string> argv = {python(),
                                   script.string(),
                                   (dir / "comparison.csv").string(),
                                   png.string(),
                                   title,
                                   std::to_string(h),
                                   std::to_string(v),
                                   num(layout.origin[v]),
                                   num(layout.origin[v] + layout.box_size[v])};
  for (const auto& m : crack_models)
    argv.push_back(m + "=" + (dir / m / "cracks.csv").string());
  const int rc = run_process(argv, log);
  if (rc == 0 && fs::exists(png))
  {
    fs::rename(png, dir / "comparison.png");
    fs::remove(log);
    return true;
  }
  std::cerr << "compare: warning: comparison.png not written; see " << log.string() << std::endl;
  return false;
}

std::string cell(const json& m, const char* key, double scale)
{
  if (!m.contains(key) || !m[key].is_number())
    return "-";
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", m[key].get<double>() * scale);
  return b;
}

/// The few figures, as a table.
void print_table(const json& result)
{
  std::printf("\n%-14s %12s %14s %12s %10s %12s %10s %10s\n", "model", "peak load N",
              "at deflection mm", "fracture J", "broken", "wall s", "memory MB", "particles");
  for (const char* name : {"coupled", "coupled_fixed", "full_dem", "full_fem"})
  {
    if (!result["models"].contains(name))
      continue;
    const json& m = result["models"][name];
    std::printf("%-14s %12s %14s %12s %10s %12s %10s %10s\n", name, cell(m, "peak_load", 1).c_str(),
                cell(m, "deflection_at_peak", 1e3).c_str(), cell(m, "fracture_energy", 1).c_str(),
                cell(m, "n_broken_bonds", 1).c_str(), cell(m, "wall_seconds", 1).c_str(),
                cell(m, "peak_memory_bytes", 1e-6).c_str(), cell(m, "n_particles", 1).c_str());
  }
  const json& vs = result["coupled_vs_full_dem"];
  std::printf("coupled / full DEM: peak load %s, limit load %s, fracture energy %s, speed-up %s\n",
              cell(vs, "peak_load_ratio", 1).c_str(), cell(vs, "limit_load_ratio", 1).c_str(),
              cell(vs, "fracture_energy_ratio", 1).c_str(), cell(vs, "speedup", 1).c_str());
  if (result.contains("coupled_vs_coupled_fixed"))
  {
    const json& c = result["models"]["coupled"];
    const json& f = result["coupled_vs_coupled_fixed"];
    std::printf("adaptive region: %s growths, %s particles at the end (%s of the envelope's "
                "packing), largest energy jump %s of the strain energy\n",
                cell(c, "n_region_growth_events", 1).c_str(),
                cell(c, "n_particles_final", 1).c_str(),
                cell(c, "particle_region_packing_fraction", 1).c_str(),
                cell(c, "growth_energy_jump_max", 1).c_str());
    std::printf("coupled (adaptive) / coupled_fixed: peak load %s, fracture energy %s, speed-up "
                "%s; coupled_fixed / full DEM: peak load %s, speed-up %s\n",
                cell(f, "peak_load_ratio", 1).c_str(), cell(f, "fracture_energy_ratio", 1).c_str(),
                cell(f, "speedup", 1).c_str(),
                cell(result["coupled_fixed_vs_full_dem"], "peak_load_ratio", 1).c_str(),
                cell(result["coupled_fixed_vs_full_dem"], "speedup", 1).c_str());
  }
}
} // namespace

int run_compare(const CompareOptions& o)
{
  const std::string case_name = fs::path(o.case_file).filename().string();
  auto in_case = [&](const std::string& msg) { return case_name + ": " + msg; };

  // ---- 1. Inputs: the case and both derived models, checked before anything runs.
  auto prm = read_case(o.case_file, o.overrides);
  if (prm->get("Mode") != "coupled")
    throw std::runtime_error(in_case("Mode: compare needs a coupled case (Mode = coupled)"));
  const fs::path case_dir = fs::absolute(o.case_file).parent_path();
  coupling::CoupledCase cc;
  coupling::FullDemLayout layout;
  coupling::FullFeModel fe_model;
  try
  {
    WorkingDirectory cd(case_dir);
    cc = parse_coupled_case(*prm);
    layout = coupling::full_dem_layout(cc);
    const double cell = o.fe_cell_size > 0 ? o.fe_cell_size : 4 * cc.particles.particles.radius;
    fe_model = coupling::full_fe_model(cc, cell, o.fe_degree);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(in_case(one_line(e.what())));
  }
  for (const auto& n : layout.notes)
    std::cerr << "compare: note: " << n << std::endl;
  const bool adaptive = cc.settings.adaptive.enabled;
  const int n_models = adaptive ? 4 : 3;
  auto step = [&](int k) { return std::to_string(k) + " of " + std::to_string(n_models); };

  // ---- 2. The output folder: the comparison's own files go first.
  const fs::path dir =
      fs::absolute(o.output_dir.empty()
                       ? fs::path("output") / ("compare_" + fs::path(o.case_file).stem().string())
                       : fs::path(o.output_dir));
  fs::create_directories(dir);
  for (const char* f : {"comparison.json", "comparison.csv", "comparison.png", "full_dem.prm",
                        "coupled_fixed.prm", "coupled_fixed_region.msh"})
    fs::remove(dir / f);

  // ---- 3. The runs: each of its own process (compare_process.h), the FE reference in this one.
  run_case_process(step(1) + ", the coupled run of " + case_name, fs::absolute(o.case_file),
                   o.overrides, dir / "coupled");
  const json coupled = read_json_file((dir / "coupled" / "summary.json").string(), "compare");
  int next = 2;
  json fixed;
  if (adaptive)
  {
    // the same case with the region the adaptive run ended with, placed at the start
    const auto cells = coupling::RegionCells::from_json(coupled.at("region_final_cells"),
                                                        "coupled/summary.json: region_final_cells");
    coupling::write_region_mesh(cells, dir / "coupled_fixed_region.msh");
    {
      dem::OutputFile out(dir / "coupled_fixed.prm");
      out << coupled_fixed_text(o, cells, dir / "coupled_fixed_region.msh");
      out.close();
    }
    run_case_process(step(next++) + ", the coupled run with the final region fixed from the start "
                                    "(coupled_fixed.prm)",
                     dir / "coupled_fixed.prm", {}, dir / "coupled_fixed");
    fixed = read_json_file((dir / "coupled_fixed" / "summary.json").string(), "compare");
  }
  const double dt = coupled.at("time_step").get<double>();
  {
    dem::OutputFile out(dir / "full_dem.prm"); // failures name the file and the reason
    out << full_dem_text(o, layout, dt);
    out.close();
  }
  run_case_process(step(next++) + ", the full-DEM run (full_dem.prm)", dir / "full_dem.prm", {},
                   dir / "full_dem");
  const json full_dem = read_json_file((dir / "full_dem" / "summary.json").string(), "compare");
  std::cout << "compare: " << step(next) << ", the elastic FE reference (into "
            << (dir / "full_fem").string() << ")" << std::endl;
  fs::create_directories(dir / "full_fem");
  const auto fe_start = std::chrono::steady_clock::now();
  json fe = run_fem_case(fe_model.parameters, dir / "full_fem", MPI_COMM_WORLD);
  fe["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - fe_start).count();
  fe["peak_memory_bytes"] = peak_memory_bytes();
  write_json_atomically(dir / "full_fem", "summary.json", fe);

  // ---- 4. The figures.
  const Vec3 direction = fe_model.load.direction;
  const std::string g = fe_model.load.group;
  const Table ch = read_csv(dir / "coupled" / "history.csv");
  const Table dh = read_csv(dir / "full_dem" / "history.csv");
  ModelCurves curves;
  curves.curves.emplace_back("coupled", coupled_curve(ch, "coupled/history.csv"));
  std::optional<Table> fh;
  if (adaptive)
  {
    fh = read_csv(dir / "coupled_fixed" / "history.csv");
    curves.curves.emplace_back("coupled_fixed", coupled_curve(*fh, "coupled_fixed/history.csv"));
  }
  curves.curves.emplace_back("full_dem", dem_curve_of(dh, g, direction, "full_dem/history.csv"));
  const Curve& cc_curve = curves.curves.front().second;
  const Curve& dem_curve = curves.curves.back().second;
  const Vec3 R(fe.at("reactions").at("load")[0].get<double>(),
               fe.at("reactions").at("load")[1].get<double>(),
               fe.at("reactions").at("load")[2].get<double>());
  const double fe_deflection = fe_model.load.displacement.norm();
  // the reaction is the support's force on the body, along the push
  const double fe_stiffness = R.dot(direction) / fe_deflection;
  curves.fe_stiffness = fe_stiffness;

  const Vec3 void_lo(fe_model.parameters.remove_lower[0], fe_model.parameters.remove_lower[1],
                     fe_model.parameters.remove_lower[2]);
  const Vec3 void_hi(fe_model.parameters.remove_upper[0], fe_model.parameters.remove_upper[1],
                     fe_model.parameters.remove_upper[2]);
  const bool notch = (void_hi - void_lo).minCoeff() > 0;
  auto model_json = [&](const json& summary, const Curve& curve, const std::vector<double>& broken,
                        double fracture_energy, const fs::path& run_dir)
  {
    json j = curve_figures(curve, broken);
    j["wall_seconds"] = summary.value("wall_seconds", 0.0);
    j["peak_memory_bytes"] = summary.value("peak_memory_bytes", 0.0);
    j["n_particles"] = summary.value("n_particles", 0L);
    j["n_broken_bonds"] = summary.value("n_broken_bonds", 0L);
    j["broken_bonds_tension"] = summary.value("broken_bonds_tension", 0L);
    j["broken_bonds_shear"] = summary.value("broken_bonds_shear", 0L);
    j["fracture_energy"] = fracture_energy;
    if (summary.contains("energy_balance_error_max"))
      j["energy_balance_error_max"] = summary["energy_balance_error_max"];
    if (summary.contains("energy_balance_error"))
      j["energy_balance_error"] = summary["energy_balance_error"];
    if (const auto x = first_crack(run_dir / "cracks.csv"))
    {
      j["first_crack"] = to_json(*x);
      if (notch)
        j["first_crack_distance_to_notch"] = distance_to_box(*x, void_lo, void_hi);
    }
    j["output"] = run_dir.string();
    return j;
  };
  // a coupled run: the fracture energy is the particle region's (no other part can break)
  auto coupled_json =
      [&](const json& summary, const Table& h, const Curve& curve, const std::string& name)
  {
    json m = model_json(summary, curve, h.get("n_broken_bonds", name + "/history.csv"),
                        summary.value("fracture_energy", 0.0), dir / name);
    m["n_fe_dofs"] = summary.value("n_fe_dofs", 0L);
    m["coupling_share"] = summary.value("coupling_share", 0.0);
    m["damage_reached_band"] = summary.value("damage_reached_band", false);
    return m;
  };
  json result;
  result["case"] = case_name;
  result["load_group"] = g;
  result["load_direction"] = to_json(direction);
  if (notch)
    result["notch"] = {{"lower", to_json(void_lo)}, {"upper", to_json(void_hi)}};
  result["same_packing"] = layout.same_packing;
  result["notes"] = layout.notes;
  for (const auto& n : fe_model.notes)
    result["notes"].push_back(n);
  json& mc = result["models"]["coupled"];
  mc = coupled_json(coupled, ch, cc_curve, "coupled");
  json& md = result["models"]["full_dem"];
  const auto dem_fracture = dh.get("fracture_energy", "full_dem/history.csv");
  md = model_json(full_dem, dem_curve, dh.get("n_broken_bonds", "full_dem/history.csv"),
                  dem_fracture.empty() ? 0.0 : dem_fracture.back(), dir / "full_dem");
  if (adaptive)
  {
    add_growth_figures(mc, coupled);
    json& mx = result["models"]["coupled_fixed"];
    mx = coupled_json(fixed, *fh, curves.curves[1].second, "coupled_fixed");
    mx["region_cells"] = coupled.at("region_cells_final");
    mx["region_file"] = (dir / "coupled_fixed_region.msh").string();
  }
  json& mf = result["models"]["full_fem"];
  mf = {{"initial_stiffness", fe_stiffness},
        {"wall_seconds", fe["wall_seconds"]},
        {"peak_memory_bytes", fe["peak_memory_bytes"]},
        {"n_dofs", fe.value("n_dofs", 0L)},
        {"degree", o.fe_degree},
        {"output", (dir / "full_fem").string()}};
  result["coupled_vs_full_dem"] = versus(mc, md);
  if (adaptive)
  {
    result["coupled_fixed_vs_full_dem"] = versus(result["models"]["coupled_fixed"], md);
    result["coupled_vs_coupled_fixed"] = versus(mc, result["models"]["coupled_fixed"]);
  }
  if (mc.contains("initial_stiffness"))
    result["coupled_vs_full_fem"]["initial_stiffness_ratio"] =
        mc["initial_stiffness"].get<double>() / fe_stiffness;
  if (md.contains("initial_stiffness"))
    result["full_dem_vs_full_fem"]["initial_stiffness_ratio"] =
        md["initial_stiffness"].get<double>() / fe_stiffness;
  result["particle_radius"] = cc.particles.particles.radius;

  // ---- 5. Files: the curves, the plot, comparison.json last.
  write_curves(dir, curves);
  result["plot"] = nullptr;
  std::vector<std::string> crack_models = {"coupled"};
  if (adaptive)
    crack_models.push_back("coupled_fixed");
  crack_models.push_back("full_dem");
  if (o.plot && write_plot(dir,
                           case_name + ": " +
                               (adaptive ? "adaptive coupled, fixed-region "
                                           "coupled, full DEM, full FE"
                                         : "coupled, full DEM, full FE"),
                           direction, layout, crack_models))
    result["plot"] = "comparison.png";
  write_json_atomically(dir, "comparison.json", result);

  // ---- 6. The few figures, as a table.
  print_table(result);
  std::printf("compare: wrote %s\n", (dir / "comparison.json").c_str());
  return 0;
}
} // namespace dembridge::app
