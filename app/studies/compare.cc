// dembridge compare: coupled against full DEM and full FE (see compare.h).
#include "app/studies/compare.h"
#include "app/input/case_file.h"
#include "app/input/coupled_parameters.h"
#include "app/input/dem_parameters.h"
#include "app/job/provenance.h"
#include "app/runs/memory_guard.h"
#include "app/studies/compare_plot.h"
#include "app/studies/verify.h"
#include "app/studies/verify_model.h"
#include "app/studies/verify_report.h"
#include "coupling/full_models.h"
#include "dem/core/output_file.h"
#include "dem/measurements/failure_measurements.h"
#include "fem/fem_case.h"
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
#include <sys/wait.h>

namespace dembridge::app
{
namespace fs = std::filesystem;
using json = nlohmann::json;
using dem::Vec3;
using verify_detail::num;
using verify_detail::python;
using verify_detail::shell_quote;
using verify_detail::write_json_atomically;

namespace
{
std::string vec_text(const Vec3& v)
{
  return num(v.x()) + ", " + num(v.y()) + ", " + num(v.z());
}

std::string dof_text(std::uint8_t mask)
{
  std::string t;
  const char* names[3] = {"ux", "uy", "uz"};
  for (int d = 0; d < 3; ++d)
    if (mask & (1u << d))
      t += (t.empty() ? "" : ", ") + std::string(names[d]);
  return t;
}

std::string component_text(std::uint8_t mask)
{
  std::string t;
  for (int d = 0; d < 3; ++d)
    if (mask & (1u << d))
      t += (t.empty() ? "" : ", ") + std::string(1, "xyz"[d]);
  return t;
}

/// Drops the top-level subsections @p names (with everything nested in them) from a PRM text.
std::string without_sections(const std::string& text, const std::vector<std::string>& names)
{
  std::istringstream in(text);
  std::ostringstream out;
  int depth = 0, skip_depth = -1;
  for (std::string line; std::getline(in, line);)
  {
    const auto first = line.find_first_not_of(' ');
    const std::string t = first == std::string::npos ? "" : line.substr(first);
    if (t.rfind("subsection ", 0) == 0)
    {
      if (depth == 0 && skip_depth < 0)
        for (const auto& n : names)
          if (t.substr(11) == n)
            skip_depth = 0;
      ++depth;
      if (skip_depth >= 0)
        continue;
    }
    else if (t == "end")
    {
      --depth;
      if (skip_depth >= 0)
      {
        if (depth == skip_depth)
          skip_depth = -1;
        continue;
      }
    }
    if (skip_depth < 0)
      out << line << '\n';
  }
  return out.str();
}

/// The full-DEM case file: the coupled case's own parameters (after --set) with the particle
/// box of the layout, the supports as groups (and driven supports as loads), the mass damping
/// and the coupled run's time step; the Coupling and FEM sections left out.
std::string full_dem_text(const CompareOptions& o, const coupling::FullDemLayout& layout,
                          double time_step)
{
  auto prm = read_case(o.case_file, o.overrides);
  const fs::path case_dir = fs::absolute(o.case_file).parent_path();
  std::vector<std::string> groups, loads;
  for (const auto& s : layout.supports)
    (s.driven ? loads : groups).push_back(s.name);
  std::vector<std::string> all_groups;
  for (const auto& s : layout.supports)
    all_groups.push_back(s.name);
  declare_group_parameters(*prm, all_groups);
  declare_load_parameters(*prm, loads);
  prm->set("Mode", "dem");
  auto join = [](std::string list, const std::vector<std::string>& more)
  {
    for (const auto& m : more)
      list += (list.find_first_not_of(" ") == std::string::npos ? "" : ", ") + m;
    return list;
  };
  prm->enter_subsection("Particles");
  prm->set("origin", vec_text(layout.origin));
  prm->set("box size", vec_text(layout.box_size));
  prm->leave_subsection();
  prm->enter_subsection("Damping");
  prm->set("mass damping", num(layout.mass_damping));
  prm->leave_subsection();
  prm->enter_subsection("Simulation");
  prm->set("time step", num(time_step));
  prm->leave_subsection();
  prm->enter_subsection("Groups");
  prm->set("names", join(prm->get("names"), all_groups));
  prm->leave_subsection();
  if (!loads.empty())
  {
    prm->enter_subsection("Loads");
    prm->set("names", join(prm->get("names"), loads));
    prm->leave_subsection();
  }
  static const char* faces[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
  for (const auto& s : layout.supports)
  {
    prm->enter_subsection("Group " + s.name);
    switch (s.selection.kind)
    {
    case dem::GroupSelection::Kind::box:
      prm->set("select", "box");
      prm->set("box min", vec_text(s.selection.box_min));
      prm->set("box max", vec_text(s.selection.box_max));
      break;
    case dem::GroupSelection::Kind::face:
      prm->set("select", "face");
      prm->set("face", faces[2 * s.selection.face_axis + (s.selection.face_upper ? 1 : 0)]);
      break;
    default:
      prm->set("select", "nearest");
      prm->set("point", vec_text(s.selection.point));
    }
    prm->set("fixed", dof_text(s.fixed));
    prm->leave_subsection();
    if (s.driven)
    {
      prm->enter_subsection("Load " + s.name);
      prm->set("group", s.name);
      prm->set("type", "displacement");
      prm->set("value", vec_text(s.displacement));
      prm->set("components", component_text(s.driven_components));
      prm->leave_subsection();
    }
  }
  std::string header = "# Full-DEM counterpart of " + fs::absolute(o.case_file).string() +
                       ", written by `dembridge compare` (coupling/full_models.h)\n";
  for (const auto& n : layout.notes)
    header += "# note: " + n + "\n";
  return without_sections(parameters_file_text(*prm, case_dir, header), {"Coupling", "FEM"});
}

/// Runs `dembridge run` in a process of its own (its memory is its own); throws with the
/// child's exit code when it fails.
json run_child(const std::string& what, const fs::path& case_file,
               const std::vector<std::string>& overrides, const fs::path& dir)
{
  std::string command = shell_quote(fs::read_symlink("/proc/self/exe").string()) + " run " +
                        shell_quote(case_file.string()) + " --output-dir " +
                        shell_quote(dir.string());
  for (const auto& s : overrides)
    command += " --set " + shell_quote(s);
  std::cout << "compare: " << what << " (into " << dir.string() << ")" << std::endl;
  const int status = std::system(command.c_str());
  const int rc = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (rc != 0)
    throw std::runtime_error("compare: " + what + " failed (exit " + std::to_string(rc) +
                             "); its message is above");
  return read_json_file((dir / "summary.json").string(), "compare");
}

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

  // ---- 2. The output folder: the comparison's own files go first.
  const fs::path dir =
      fs::absolute(o.output_dir.empty()
                       ? fs::path("output") / ("compare_" + fs::path(o.case_file).stem().string())
                       : fs::path(o.output_dir));
  fs::create_directories(dir);
  for (const char* f : {"comparison.json", "comparison.csv", "comparison.png", "full_dem.prm"})
    fs::remove(dir / f);

  // ---- 3. The runs.
  json coupled = run_child("1 of 3, the coupled run of " + case_name, fs::absolute(o.case_file),
                           o.overrides, dir / "coupled");
  const double dt = coupled.at("time_step").get<double>();
  {
    dem::OutputFile out(dir / "full_dem.prm"); // failures name the file and the reason
    out << full_dem_text(o, layout, dt);
    out.close();
  }
  json full_dem = run_child("2 of 3, the full-DEM run (full_dem.prm)", dir / "full_dem.prm", {},
                            dir / "full_dem");
  std::cout << "compare: 3 of 3, the elastic FE reference (into " << (dir / "full_fem").string()
            << ")" << std::endl;
  fs::create_directories(dir / "full_fem");
  const auto fe_start = std::chrono::steady_clock::now();
  json fe = fem::run_case(fe_model.parameters, dir / "full_fem", MPI_COMM_WORLD);
  fe["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - fe_start).count();
  fe["peak_memory_bytes"] = peak_memory_bytes();
  write_json_atomically(dir / "full_fem", "summary.json", fe);

  // ---- 4. The figures.
  const Vec3 direction = fe_model.load.direction;
  const std::string g = fe_model.load.group;
  const Table ch = read_csv(dir / "coupled" / "history.csv");
  const Table dh = read_csv(dir / "full_dem" / "history.csv");
  Curve cc_curve{ch.get("load_displacement", "coupled/history.csv"),
                 ch.get("load", "coupled/history.csv")};
  Curve dem_curve;
  {
    const std::string f = "full_dem/history.csv";
    std::vector<double> u[3], F[3];
    for (int d = 0; d < 3; ++d)
    {
      u[d] = dh.get(g + "_u" + std::string(1, "xyz"[d]), f);
      F[d] = dh.get(g + "_f" + std::string(1, "xyz"[d]), f);
    }
    for (std::size_t k = 0; k < dh.rows.size(); ++k)
    {
      dem_curve.deflection.push_back(u[0][k] * direction.x() + u[1][k] * direction.y() +
                                     u[2][k] * direction.z());
      dem_curve.load.push_back(F[0][k] * direction.x() + F[1][k] * direction.y() +
                               F[2][k] * direction.z());
    }
  }
  const Vec3 R(fe.at("reactions").at("load")[0].get<double>(),
               fe.at("reactions").at("load")[1].get<double>(),
               fe.at("reactions").at("load")[2].get<double>());
  const double fe_deflection = fe_model.load.displacement.norm();
  // the reaction is the support's force on the body, along the push
  const double fe_stiffness = R.dot(direction) / fe_deflection;

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
  // coupled: the fracture energy is the particle region's (no other part can break)
  json& mc = result["models"]["coupled"];
  mc = model_json(coupled, cc_curve, ch.get("n_broken_bonds", "coupled/history.csv"),
                  coupled.value("fracture_energy", 0.0), dir / "coupled");
  mc["n_fe_dofs"] = coupled.value("n_fe_dofs", 0L);
  mc["coupling_share"] = coupled.value("coupling_share", 0.0);
  mc["damage_reached_band"] = coupled.value("damage_reached_band", false);
  json& md = result["models"]["full_dem"];
  const auto dem_fracture = dh.get("fracture_energy", "full_dem/history.csv");
  md = model_json(full_dem, dem_curve, dh.get("n_broken_bonds", "full_dem/history.csv"),
                  dem_fracture.empty() ? 0.0 : dem_fracture.back(), dir / "full_dem");
  json& mf = result["models"]["full_fem"];
  mf = {{"initial_stiffness", fe_stiffness},
        {"wall_seconds", fe["wall_seconds"]},
        {"peak_memory_bytes", fe["peak_memory_bytes"]},
        {"n_dofs", fe.value("n_dofs", 0L)},
        {"degree", o.fe_degree},
        {"output", (dir / "full_fem").string()}};
  json& vs = result["coupled_vs_full_dem"];
  auto ratio = [&](const char* key) -> json
  {
    if (!mc.contains(key) || !md.contains(key) || md[key].get<double>() == 0)
      return nullptr;
    return mc[key].get<double>() / md[key].get<double>();
  };
  vs["peak_load_ratio"] = ratio("peak_load");
  vs["deflection_at_peak_ratio"] = ratio("deflection_at_peak");
  vs["limit_load_ratio"] = ratio("limit_load");
  vs["deflection_at_limit_ratio"] = ratio("deflection_at_limit");
  vs["fracture_energy_ratio"] = ratio("fracture_energy");
  vs["n_broken_bonds_ratio"] = ratio("n_broken_bonds");
  vs["initial_stiffness_ratio"] = ratio("initial_stiffness");
  vs["peak_memory_ratio"] = ratio("peak_memory_bytes");
  vs["speedup"] = mc["wall_seconds"].get<double>() > 0
                      ? json(md["wall_seconds"].get<double>() / mc["wall_seconds"].get<double>())
                      : json(nullptr);
  if (mc.contains("first_crack") && md.contains("first_crack"))
  {
    const Vec3 a(mc["first_crack"][0].get<double>(), mc["first_crack"][1].get<double>(),
                 mc["first_crack"][2].get<double>());
    const Vec3 b(md["first_crack"][0].get<double>(), md["first_crack"][1].get<double>(),
                 md["first_crack"][2].get<double>());
    vs["first_crack_distance"] = (a - b).norm();
  }
  if (mc.contains("initial_stiffness"))
    result["coupled_vs_full_fem"]["initial_stiffness_ratio"] =
        mc["initial_stiffness"].get<double>() / fe_stiffness;
  if (md.contains("initial_stiffness"))
    result["full_dem_vs_full_fem"]["initial_stiffness_ratio"] =
        md["initial_stiffness"].get<double>() / fe_stiffness;
  result["particle_radius"] = cc.particles.particles.radius;

  // ---- 5. Files: the curves, the plot, comparison.json last.
  {
    const fs::path part = dir / "comparison.csv.part";
    dem::OutputFile out(part); // failures name the file and the reason
    out << "model,deflection,load\n" << std::setprecision(10);
    for (std::size_t k = 0; k < cc_curve.load.size(); ++k)
      out << "coupled," << cc_curve.deflection[k] << ',' << cc_curve.load[k] << '\n';
    for (std::size_t k = 0; k < dem_curve.load.size(); ++k)
      out << "full_dem," << dem_curve.deflection[k] << ',' << dem_curve.load[k] << '\n';
    double top = 0, most = 0; // the elastic line up to a quarter above the largest load
    for (std::size_t k = 0; k < cc_curve.load.size(); ++k)
      top = std::max(top, cc_curve.deflection[k]), most = std::max(most, cc_curve.load[k]);
    if (fe_stiffness > 0 && most > 0)
      top = std::min(top, 1.25 * most / fe_stiffness);
    out << "full_fem,0,0\nfull_fem," << top << ',' << fe_stiffness * top << '\n';
    out.close();
    fs::rename(part, dir / "comparison.csv");
  }
  result["plot"] = nullptr;
  if (o.plot)
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
    const std::string command =
        shell_quote(python()) + " " + shell_quote(script.string()) + " " +
        shell_quote((dir / "comparison.csv").string()) + " " + shell_quote(png.string()) + " " +
        shell_quote(case_name + ": coupled, full DEM, full FE") + " " +
        shell_quote((dir / "coupled" / "cracks.csv").string()) + " " +
        shell_quote((dir / "full_dem" / "cracks.csv").string()) + " " + std::to_string(h) + " " +
        std::to_string(v) + " " + num(layout.origin[v]) + " " +
        num(layout.origin[v] + layout.box_size[v]) + " > " + shell_quote(log.string()) + " 2>&1";
    const int status = std::system(command.c_str());
    if (status == 0 && fs::exists(png))
    {
      fs::rename(png, dir / "comparison.png");
      fs::remove(log);
      result["plot"] = "comparison.png";
    }
    else
      std::cerr << "compare: warning: comparison.png not written; see " << log.string()
                << std::endl;
  }
  write_json_atomically(dir, "comparison.json", result);

  // ---- 6. The few figures, as a table.
  auto cell = [](const json& m, const char* key, double scale) -> std::string
  {
    if (!m.contains(key) || !m[key].is_number())
      return "-";
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", m[key].get<double>() * scale);
    return b;
  };
  std::printf("\n%-12s %12s %14s %12s %10s %12s %10s\n", "model", "peak load N", "at deflection mm",
              "fracture J", "broken", "wall s", "memory MB");
  for (const char* name : {"coupled", "full_dem", "full_fem"})
  {
    const json& m = result["models"][name];
    std::printf("%-12s %12s %14s %12s %10s %12s %10s\n", name, cell(m, "peak_load", 1).c_str(),
                cell(m, "deflection_at_peak", 1e3).c_str(), cell(m, "fracture_energy", 1).c_str(),
                cell(m, "n_broken_bonds", 1).c_str(), cell(m, "wall_seconds", 1).c_str(),
                cell(m, "peak_memory_bytes", 1e-6).c_str());
  }
  std::printf("coupled / full DEM: peak load %s, limit load %s, fracture energy %s, speed-up %s\n",
              cell(vs, "peak_load_ratio", 1).c_str(), cell(vs, "limit_load_ratio", 1).c_str(),
              cell(vs, "fracture_energy_ratio", 1).c_str(), cell(vs, "speedup", 1).c_str());
  std::printf("compare: wrote %s\n", (dir / "comparison.json").c_str());
  return 0;
}
} // namespace dembridge::app
