// dembridge compare: coupled against full DEM and full FE (see compare.h).
#include "app/studies/compare.h"
#include "app/input/case_file.h"
#include "app/input/coupled_parameters.h"
#include "app/input/dem_parameters.h"
#include "app/job/provenance.h"
#include "app/output/dem_figures.h"
#include "app/runs/fem_run.h"
#include "app/runs/memory_guard.h"
#include "app/studies/compare_cases.h"
#include "app/studies/compare_figures.h"
#include "app/studies/compare_plot.h"
#include "app/studies/compare_process.h"
#include "app/studies/verify.h"
#include "app/studies/verify_report.h"
#include "coupling/fixed_region.h"
#include "coupling/full_models.h"
#include "dem/core/output_file.h"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>

namespace dembridge::app
{
namespace fs = std::filesystem;
using json = nlohmann::json;
using compare_detail::add_growth_figures;
using compare_detail::coupled_curve;
using compare_detail::coupled_model_figures;
using compare_detail::Curve;
using compare_detail::dem_curve_of;
using compare_detail::model_figures;
using compare_detail::ModelCurves;
using compare_detail::Notch;
using compare_detail::read_csv;
using compare_detail::Table;
using compare_detail::versus;
using dem::Vec3;
using verify_detail::num;
using verify_detail::python;
using verify_detail::write_json_atomically;

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
/// The coupled case and the two models derived from it (full DEM, full FE), all checked before
/// anything runs.
struct CompareCases
{
  std::string name; ///< the case file's name
  coupling::CoupledCase coupled;
  coupling::FullDemLayout layout;
  coupling::FullFeModel fe_model;
  bool adaptive = false; ///< a fourth model: the adaptive run's final region fixed from the start
  /// "k of n": the progress of the models' runs.
  std::string step(int k) const
  {
    return std::to_string(k) + " of " + std::to_string(adaptive ? 4 : 3);
  }
};

CompareCases build_cases(const CompareOptions& o)
{
  CompareCases c;
  c.name = fs::path(o.case_file).filename().string();
  auto in_case = [&](const std::string& msg) { return c.name + ": " + msg; };
  auto prm = read_case(o.case_file, o.overrides);
  if (prm->get("Mode") != "coupled")
    throw std::runtime_error(in_case("Mode: compare needs a coupled case (Mode = coupled)"));
  const fs::path case_dir = fs::absolute(o.case_file).parent_path();
  try
  {
    WorkingDirectory cd(case_dir);
    c.coupled = parse_coupled_case(*prm);
    c.layout = coupling::full_dem_layout(c.coupled);
    const double cell =
        o.fe_cell_size > 0 ? o.fe_cell_size : 4 * c.coupled.particles.particles.radius;
    c.fe_model = coupling::full_fe_model(c.coupled, cell, o.fe_degree);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(in_case(one_line(e.what())));
  }
  for (const auto& n : c.layout.notes)
    std::cerr << "compare: note: " << n << std::endl;
  c.adaptive = c.coupled.settings.adaptive.enabled;
  return c;
}

/// The output folder (absolute), emptied of the comparison's own files: they go first.
fs::path prepare_output_folder(const CompareOptions& o)
{
  const fs::path dir =
      fs::absolute(o.output_dir.empty()
                       ? fs::path("output") / ("compare_" + fs::path(o.case_file).stem().string())
                       : fs::path(o.output_dir));
  fs::create_directories(dir);
  for (const char* f : {"comparison.json", "comparison.csv", "comparison.png", "full_dem.prm",
                        "coupled_fixed.prm", "coupled_fixed_region.msh"})
    fs::remove(dir / f);
  return dir;
}

/// The summaries of the models' runs (coupled_fixed: adaptive cases only, else null).
struct ModelSummaries
{
  json coupled, coupled_fixed, full_dem, full_fem;
};

/// The same case with the region the adaptive run ended with, placed at the start: its region
/// mesh, its case file and its run (step @p k); returns its summary.
json run_coupled_fixed(const CompareOptions& o, const CompareCases& c, const json& coupled,
                       const fs::path& dir, int k)
{
  const auto cells = coupling::RegionCells::from_json(coupled.at("region_final_cells"),
                                                      "coupled/summary.json: region_final_cells");
  coupling::write_region_mesh(cells, dir / "coupled_fixed_region.msh");
  {
    dem::OutputFile out(dir / "coupled_fixed.prm");
    out << coupled_fixed_text(o, cells, dir / "coupled_fixed_region.msh");
    out.close();
  }
  run_case_process(c.step(k) + ", the coupled run with the final region fixed from the start "
                               "(coupled_fixed.prm)",
                   dir / "coupled_fixed.prm", {}, dir / "coupled_fixed");
  return read_json_file((dir / "coupled_fixed" / "summary.json").string(), "compare");
}

/// The elastic FE reference, in this process (step @p k); returns its summary, with its wall
/// time and peak memory.
json run_full_fem(const CompareCases& c, const fs::path& dir, int k)
{
  std::cout << "compare: " << c.step(k) << ", the elastic FE reference (into "
            << (dir / "full_fem").string() << ")" << std::endl;
  fs::create_directories(dir / "full_fem");
  const auto fe_start = std::chrono::steady_clock::now();
  json fe = run_fem_case(c.fe_model.parameters, dir / "full_fem", MPI_COMM_WORLD);
  fe["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - fe_start).count();
  fe["peak_memory_bytes"] = peak_memory_bytes();
  write_json_atomically(dir / "full_fem", "summary.json", fe);
  return fe;
}

/// Runs the models: the particle ones each in a process of its own (compare_process.h), the FE
/// reference in this one. The full-DEM run takes the coupled run's time step.
ModelSummaries run_models(const CompareOptions& o, const CompareCases& c, const fs::path& dir)
{
  ModelSummaries s;
  run_case_process(c.step(1) + ", the coupled run of " + c.name, fs::absolute(o.case_file),
                   o.overrides, dir / "coupled");
  s.coupled = read_json_file((dir / "coupled" / "summary.json").string(), "compare");
  int next = 2;
  if (c.adaptive)
    s.coupled_fixed = run_coupled_fixed(o, c, s.coupled, dir, next++);
  const double dt = s.coupled.at("time_step").get<double>();
  {
    dem::OutputFile out(dir / "full_dem.prm"); // failures name the file and the reason
    out << full_dem_text(o, c.layout, dt);
    out.close();
  }
  run_case_process(c.step(next++) + ", the full-DEM run (full_dem.prm)", dir / "full_dem.prm", {},
                   dir / "full_dem");
  s.full_dem = read_json_file((dir / "full_dem" / "summary.json").string(), "compare");
  s.full_fem = run_full_fem(c, dir, next);
  return s;
}

/// The particle runs' histories and the load-deflection curves read from them.
struct ModelHistories
{
  Table coupled, full_dem;
  std::optional<Table> coupled_fixed;
  ModelCurves curves;
};

ModelHistories read_histories(const CompareCases& c, const fs::path& dir)
{
  ModelHistories h;
  h.coupled = read_csv(dir / "coupled" / "history.csv");
  h.full_dem = read_csv(dir / "full_dem" / "history.csv");
  h.curves.curves.emplace_back("coupled", coupled_curve(h.coupled, "coupled/history.csv"));
  if (c.adaptive)
  {
    h.coupled_fixed = read_csv(dir / "coupled_fixed" / "history.csv");
    h.curves.curves.emplace_back("coupled_fixed",
                                 coupled_curve(*h.coupled_fixed, "coupled_fixed/history.csv"));
  }
  h.curves.curves.emplace_back("full_dem",
                               dem_curve_of(h.full_dem, c.fe_model.load.group,
                                            c.fe_model.load.direction, "full_dem/history.csv"));
  return h;
}

/// The FE reference's stiffness: its load reaction along the push over the deflection.
double fe_stiffness_of(const json& fe, const coupling::FullFeModel& m)
{
  const Vec3 R(fe.at("reactions").at("load")[0].get<double>(),
               fe.at("reactions").at("load")[1].get<double>(),
               fe.at("reactions").at("load")[2].get<double>());
  const double fe_deflection = m.load.displacement.norm();
  // the reaction is the support's force on the body, along the push
  return R.dot(m.load.direction) / fe_deflection;
}

Notch notch_of(const coupling::FullFeModel& m)
{
  Notch n;
  n.lower = Vec3(m.parameters.remove_lower[0], m.parameters.remove_lower[1],
                 m.parameters.remove_lower[2]);
  n.upper = Vec3(m.parameters.remove_upper[0], m.parameters.remove_upper[1],
                 m.parameters.remove_upper[2]);
  n.present = (n.upper - n.lower).minCoeff() > 0;
  return n;
}

/// comparison.json's models: each particle model's figures, the adaptive run's growth, the FE
/// reference's stiffness, time and memory.
void add_model_figures(json& result, const CompareOptions& o, const CompareCases& c,
                       const ModelSummaries& s, const ModelHistories& h, const fs::path& dir,
                       const Notch& notch)
{
  const auto& curves = h.curves.curves;
  json& mc = result["models"]["coupled"];
  mc = coupled_model_figures(s.coupled, h.coupled, curves.front().second, "coupled", dir, notch);
  json& md = result["models"]["full_dem"];
  const auto dem_fracture = h.full_dem.get("fracture_energy", "full_dem/history.csv");
  md = model_figures(s.full_dem, curves.back().second,
                     h.full_dem.get("n_broken_bonds", "full_dem/history.csv"),
                     dem_fracture.empty() ? 0.0 : dem_fracture.back(), dir / "full_dem", notch);
  if (c.adaptive)
  {
    add_growth_figures(mc, s.coupled);
    json& mx = result["models"]["coupled_fixed"];
    mx = coupled_model_figures(s.coupled_fixed, *h.coupled_fixed, curves[1].second, "coupled_fixed",
                               dir, notch);
    mx["region_cells"] = s.coupled.at("region_cells_final");
    mx["region_file"] = (dir / "coupled_fixed_region.msh").string();
  }
  json& mf = result["models"]["full_fem"];
  mf = {{"initial_stiffness", h.curves.fe_stiffness},
        {"wall_seconds", s.full_fem.at("wall_seconds")},
        {"peak_memory_bytes", s.full_fem.at("peak_memory_bytes")},
        {"n_dofs", s.full_fem.value("n_dofs", 0L)},
        {"degree", o.fe_degree},
        {"output", (dir / "full_fem").string()}};
}

/// comparison.json's pairs: the coupled run (and the fixed-region one) against full DEM, the
/// adaptive run against the fixed-region one, and the initial stiffnesses against full FE.
void add_model_ratios(json& result, bool adaptive, double fe_stiffness)
{
  const json& mc = result["models"]["coupled"];
  const json& md = result["models"]["full_dem"];
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
}

/// comparison.json's figures: the case, its load and notch, each model's figures and each
/// pair's ratios.
json collect_figures(const CompareOptions& o, const CompareCases& c, const ModelSummaries& s,
                     const ModelHistories& h, const fs::path& dir)
{
  const Notch notch = notch_of(c.fe_model);
  json result;
  result["case"] = c.name;
  result["load_group"] = c.fe_model.load.group;
  result["load_direction"] = to_json(c.fe_model.load.direction);
  if (notch.present)
    result["notch"] = {{"lower", to_json(notch.lower)}, {"upper", to_json(notch.upper)}};
  result["same_packing"] = c.layout.same_packing;
  result["notes"] = c.layout.notes;
  for (const auto& n : c.fe_model.notes)
    result["notes"].push_back(n);
  add_model_figures(result, o, c, s, h, dir, notch);
  add_model_ratios(result, c.adaptive, h.curves.fe_stiffness);
  result["particle_radius"] = c.coupled.particles.particles.radius;
  return result;
}

/// The files: the curves, the plot (unless --no-plot), comparison.json last.
void write_comparison(const CompareOptions& o, const CompareCases& c, const ModelCurves& curves,
                      const fs::path& dir, json& result)
{
  write_curves(dir, curves);
  result["plot"] = nullptr;
  std::vector<std::string> crack_models = {"coupled"};
  if (c.adaptive)
    crack_models.push_back("coupled_fixed");
  crack_models.push_back("full_dem");
  const std::string title =
      c.name + ": " +
      (c.adaptive ? "adaptive coupled, fixed-region coupled, full DEM, full FE"
                  : "coupled, full DEM, full FE");
  if (o.plot && write_plot(dir, title, c.fe_model.load.direction, c.layout, crack_models))
    result["plot"] = "comparison.png";
  write_json_atomically(dir, "comparison.json", result);
}
} // namespace

int run_compare(const CompareOptions& o)
{
  const CompareCases cases = build_cases(o);
  const fs::path dir = prepare_output_folder(o);
  const ModelSummaries summaries = run_models(o, cases, dir);
  ModelHistories histories = read_histories(cases, dir);
  histories.curves.fe_stiffness = fe_stiffness_of(summaries.full_fem, cases.fe_model);
  json result = collect_figures(o, cases, summaries, histories, dir);
  write_comparison(o, cases, histories.curves, dir, result);
  print_table(result);
  std::printf("compare: wrote %s\n", (dir / "comparison.json").c_str());
  return 0;
}
} // namespace dembridge::app
