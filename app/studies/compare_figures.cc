// dembridge compare: the figures of the runs (see compare_figures.h).
#include "app/studies/compare_figures.h"
#include "app/output/dem_figures.h"
#include "dem/measurements/failure_measurements.h"
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dembridge::app::compare_detail
{
namespace fs = std::filesystem;
using json = nlohmann::json;
using dem::Vec3;

std::vector<double> Table::get(const std::string& name, const std::string& file) const
{
  const auto it = column.find(name);
  if (it == column.end())
    throw std::runtime_error("compare: " + file + " has no column '" + name + "'");
  std::vector<double> v;
  for (const auto& r : rows)
    v.push_back(it->second < r.size() ? r[it->second] : std::nan(""));
  return v;
}

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

namespace
{
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
} // namespace

Curve coupled_curve(const Table& h, const std::string& file)
{
  return {h.get("load_displacement", file), h.get("load", file)};
}

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

json model_figures(const json& summary, const Curve& curve, const std::vector<double>& broken,
                   double fracture_energy, const fs::path& run_dir, const Notch& notch)
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
    if (notch.present)
      j["first_crack_distance_to_notch"] = distance_to_box(*x, notch.lower, notch.upper);
  }
  j["output"] = run_dir.string();
  return j;
}

json coupled_model_figures(const json& summary, const Table& h, const Curve& curve,
                           const std::string& name, const fs::path& dir, const Notch& notch)
{
  json m = model_figures(summary, curve, h.get("n_broken_bonds", name + "/history.csv"),
                         summary.value("fracture_energy", 0.0), dir / name, notch);
  m["n_fe_dofs"] = summary.value("n_fe_dofs", 0L);
  m["coupling_share"] = summary.value("coupling_share", 0.0);
  m["damage_reached_band"] = summary.value("damage_reached_band", false);
  return m;
}

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

void add_growth_figures(json& model, const json& summary)
{
  for (const char* key : {"n_region_growth_events", "n_particles_final", "growth_energy_jump_max",
                          "particle_region_packing_fraction", "region_cells_final",
                          "max_utilisation", "region_growth_capped"})
    if (summary.contains(key))
      model[key] = summary[key];
}
} // namespace dembridge::app::compare_detail
