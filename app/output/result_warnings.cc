#include "app/output/result_warnings.h"
#include "dem/model/bond_coverage.h"
#include <cmath>
#include <cstdio>
#include <sstream>

namespace dembridge::app
{
void add_warning(nlohmann::json& summary, const std::string& line, bool print)
{
  if (!summary.contains("warnings") || !summary["warnings"].is_array())
    summary["warnings"] = nlohmann::json::array();
  summary["warnings"].push_back(line);
  if (print)
  {
    std::fprintf(stderr, "dembridge: warning: %s\n", line.c_str());
    std::fflush(stderr);
  }
}

namespace
{
bool warned_about(const nlohmann::json& summary, const std::string& key)
{
  if (!summary.contains("warnings"))
    return false;
  for (const auto& w : summary["warnings"])
    if (w.is_string() && w.get<std::string>().rfind(key + ":", 0) == 0)
      return true;
  return false;
}

/// Collects the paths of the non-finite numbers below @p node ("a.b", "a.0" for arrays).
void find_undefined(nlohmann::json& node, const std::string& path,
                    std::vector<std::pair<std::string, double>>& found)
{
  if (node.is_number_float())
  {
    const double v = node.get<double>();
    if (!std::isfinite(v))
    {
      found.emplace_back(path, v);
      node = nullptr;
    }
    return;
  }
  if (node.is_object())
    for (auto& [key, child] : node.items())
      find_undefined(child, path.empty() ? key : path + "." + key, found);
  else if (node.is_array())
    for (std::size_t k = 0; k < node.size(); ++k)
      find_undefined(node[k], path + "." + std::to_string(k), found);
}
} // namespace

void flag_undefined_figures(nlohmann::json& summary, bool print)
{
  if (!summary.contains("warnings") || !summary["warnings"].is_array())
    summary["warnings"] = nlohmann::json::array();
  std::vector<std::pair<std::string, double>> found;
  for (auto& [key, child] : summary.items())
    if (key != "warnings")
      find_undefined(child, key, found);
  for (const auto& [path, v] : found)
    if (!warned_about(summary, path))
      add_warning(summary,
                  path + ": undefined (" +
                      (std::isnan(v) ? "nan"
                       : v > 0       ? "inf"
                                     : "-inf") +
                      "): the run could not measure it; written as null",
                  print);
}

void check_bond_coverage(const dem::ParticleStore& p, std::size_t n_bonds,
                         const dem::CaseConfig& config, nlohmann::json& summary, bool print)
{
  const bool breaks = config.damage.law.mode != dem::FailureMode::none;
  const dem::BondCoverage c = dem::bond_coverage(p);
  std::ostringstream need;
  need.precision(4);
  if (c.closest_pair_multiplier > 0)
  {
    need << "a multiplier of at least " << c.closest_pair_multiplier
         << " bonds the closest pair (their centre distance over their radii's sum)";
    if (c.every_particle_multiplier > 0)
      need << ", " << c.every_particle_multiplier
           << " bonds every particle to its nearest neighbour";
  }
  else
    need << "no two particles lie within twice their radii's sum of each other";
  if (n_bonds == 0)
  {
    if (!breaks)
      return; // contacts alone: a granular model (build_model refuses one without contacts)
    std::ostringstream s;
    s.precision(4);
    s << "Bonds/contact radius multiplier: " << config.bonds.contact_radius_multiplier
      << " forms no bond, and this specimen has a failure law (Damage/failure) for bonds to "
         "break: "
      << need.str();
    throw dem::InputError(s.str());
  }
  if (c.unbonded == 0)
    return;
  std::ostringstream s;
  s.precision(4);
  s << "n_unbonded_particles: " << c.unbonded << " of the " << p.size()
    << " particles have no bond (held by nothing but contacts and supports); "
       "Bonds/contact radius multiplier is "
    << config.bonds.contact_radius_multiplier << ": " << need.str();
  summary["n_unbonded_particles"] = c.unbonded;
  add_warning(summary, s.str(), print);
}

void check_explicit_end_time(double end_time, const std::string& save_file)
{
  if (end_time > 0 || (end_time == 0 && !save_file.empty()))
    return;
  throw dem::InputError("Simulation/end time: an explicit run needs a positive end time (the "
                        "simulated time, s; " +
                        std::string(end_time == 0 ? "0" : "this one") +
                        " would take one step and measure nothing; 0 only writes a packing, with "
                        "Particles/save file)");
}
} // namespace dembridge::app
