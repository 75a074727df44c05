#include "app/job/provenance.h"
#include "app/job/version.h"
#include "app/input/case_scan.h"
#include "dem/core/output_file.h"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <deal.II/base/multithread_info.h>
#include <optional>
#include <sstream>
#include <unistd.h>

namespace dembridge::app
{
namespace fs = std::filesystem;

namespace
{
std::vector<std::string> command_line_words;

/// deal.II's short PRM text: "set key = value", "subsection Name", "end"; every entry.
std::string short_prm(const dealii::ParameterHandler& prm)
{
  std::ostringstream text;
  prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
  return text.str();
}

/// Entries that name files; relative paths are relative to the case file's folder.
bool is_path_entry(const std::vector<std::string>& sections, const std::string& key)
{
  const std::vector<std::string> particles{"Particles"}, mesh{"FEM", "Mesh"}, coupling{"Coupling"};
  return (sections == particles &&
          (key == "file" || key == "save file" || key == "specimen volume")) ||
         (sections == mesh && key == "file") ||
         (sections == coupling && (key == "tensor file" || key == "particle region file"));
}

/// @p text with every set line replaced by what @p visit(path, key, value, line) returns.
template <class Visit> std::string for_each_entry(const std::string& text, Visit visit)
{
  return rewrite_prm_lines(text,
                           [&](const PrmLine& l) -> std::optional<std::string>
                           {
                             if (l.kind != PrmLine::Kind::set || !l.well_formed)
                               return l.text;
                             return visit(l.path, l.key, l.value, l.text);
                           });
}
} // namespace

void set_command_line(int argc, const char* const* argv)
{
  command_line_words.assign(argv, argv + argc);
}

const std::vector<std::string>& command_line()
{
  return command_line_words;
}

nlohmann::json parameters_json(const dealii::ParameterHandler& prm)
{
  nlohmann::json j = nlohmann::json::object();
  for_each_entry(short_prm(prm),
                 [&](const std::vector<std::string>& sections, const std::string& key,
                     const std::string& value, const std::string& line)
                 {
                   nlohmann::json* node = &j;
                   for (const auto& s : sections)
                     node = &(*node)[s];
                   (*node)[key] = value;
                   return line;
                 });
  return j;
}

std::string parameters_file_text(const dealii::ParameterHandler& prm, const fs::path& case_dir,
                                 const std::string& header)
{
  const std::string body = for_each_entry(
      short_prm(prm),
      [&](const std::vector<std::string>& sections, const std::string& key,
          const std::string& value, const std::string& line)
      {
        if (value.empty() || !is_path_entry(sections, key) || fs::path(value).is_absolute())
          return line;
        // An input that is not beside the case (a mesh the build generated, found by name) keeps
        // its relative name; outputs (save file) go where the original run wrote them.
        const fs::path resolved = (case_dir / value).lexically_normal();
        if (key != "save file" && !fs::exists(resolved))
          return line;
        return line.substr(0, line.find('=') + 1) + " " + resolved.string();
      });
  return header + body;
}

void write_parameters_file(const dealii::ParameterHandler& prm, const fs::path& case_file,
                           const fs::path& file)
{
  const std::string header =
      "# The complete parameter set of a dembridge run (every entry, after --set),\n"
      "# written by dembridge " +
      version() + " (git commit " + git_commit() +
      ")\n"
      "# from " +
      fs::absolute(case_file).string() +
      "\n"
      "# Rerun: dembridge run " +
      file.filename().string() + "\n";
  dem::OutputFile out(file); // failures name the file and the reason
  out << parameters_file_text(prm, fs::absolute(case_file).parent_path(), header);
  out.close();
}

std::string utc_now()
{
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

nlohmann::json provenance(const dealii::ParameterHandler& prm, const std::string& started_at)
{
  char host[256] = "unknown";
  if (gethostname(host, sizeof host) != 0)
    std::snprintf(host, sizeof host, "unknown");
  host[sizeof host - 1] = '\0';
  nlohmann::json j;
  j["version"] = version();
  j["git_commit"] = git_commit();
  j["command_line"] = command_line();
  j["host"] = host;
  j["started_at"] = started_at;
  j["parameters"] = parameters_json(prm);
  // DEM threads are a case parameter; the FE layer runs one thread per MPI rank.
  const auto& simulation = j["parameters"]["Simulation"];
  j["threads"] = j["parameters"].value("Mode", "dem") != "fem" && simulation.contains("threads")
                     ? std::stoi(simulation["threads"].get<std::string>())
                     : int(dealii::MultithreadInfo::n_threads());
  return j;
}

namespace
{
/// The figures `run` prints, in this order, with their units.
struct Figure
{
  const char* key; ///< a path: "first_crack.position" is summary["first_crack"]["position"]
  const char* unit;
};
const Figure printed_figures[] = {
    {"tip_deflection", "m"},
    {"midspan_deflection", "m"},
    {"deflection", "m"},
    {"natural_frequency", "Hz"},
    {"youngs_modulus", "Pa"},
    {"youngs_modulus_fit", "Pa"},
    {"poisson_ratio_xy", ""},
    {"poisson_ratio_xz", ""},
    {"poisson_ratio_yx", ""},
    {"poisson_ratio_yz", ""},
    {"poisson_ratio_zx", ""},
    {"poisson_ratio_zy", ""},
    {"flexural_modulus", "Pa"},
    {"final_secant_modulus", "Pa"},
    {"boundary_stress", "Pa"},
    {"reaction_force", "N"},
    // failure: the peak, where it came, how far past it the run went, what broke and where
    {"peak_stress", "Pa"},
    {"strain_at_peak", ""},
    {"peak_load", "N"},
    {"deflection_at_peak", "m"},
    {"final_to_peak_load", ""},
    {"n_broken_bonds", ""},
    {"broken_bonds_tension", ""},
    {"broken_bonds_shear", ""},
    {"first_crack.position", "m"},
    {"damage_layers.localisation", ""},
    {"strain_energy", "J"},
    {"energy_balance_error", ""},
    {"kinetic_energy_share_max", ""},
    {"shadow_energy_relative_drift", ""},
    {"geometry", ""},
    {"max_rotation", "rad"},
    {"porosity", ""},
    {"mean_coordination", ""},
    {"n_particles", ""},
    {"n_bonds", ""},
    {"n_unbonded_particles", ""},
    {"n_dofs", ""},
    {"steps", ""},
    {"simulated_time", "s"},
    {"stop_reason", ""},
};

std::string number_text(const nlohmann::json& v)
{
  if (v.is_number_integer() || v.is_number_unsigned())
    return std::to_string(v.get<long long>());
  char text[32];
  std::snprintf(text, sizeof text, "%.8g", v.get<double>());
  return std::string(text);
}

/// The value at @p key ("first_crack.position": summary["first_crack"]["position"]), or null.
const nlohmann::json* figure_at(const nlohmann::json& summary, const char* key)
{
  const nlohmann::json* v = &summary;
  std::istringstream path(key);
  for (std::string part; v && std::getline(path, part, '.');)
    v = v->is_object() && v->contains(part) ? &(*v)[part] : nullptr;
  return v;
}

/// A figure as printed: a number, a text, "undefined" for null (its warning says why), numbers
/// of an array joined by commas; nothing for anything else (not printed).
std::optional<std::string> figure_text(const nlohmann::json& v)
{
  std::string value;
  if (v.is_number())
    value = number_text(v);
  else if (v.is_string())
    value = v.get<std::string>();
  else if (v.is_null())
    value = "undefined";
  else if (v.is_array() && !v.empty() &&
           std::all_of(v.begin(), v.end(), [](const auto& x) { return x.is_number(); }))
    for (const auto& x : v)
      value += (value.empty() ? "" : ", ") + number_text(x);
  else
    return std::nullopt;
  return value;
}
} // namespace

void print_figures(const nlohmann::json& summary, std::ostream& out)
{
  out << "\nfigures of this run (summary.json):\n";
  char line[400];
  for (const auto& f : printed_figures)
  {
    const nlohmann::json* v = figure_at(summary, f.key);
    if (!v)
      continue;
    const std::optional<std::string> value = figure_text(*v);
    if (!value)
      continue;
    std::snprintf(line, sizeof line, "  %-28s %16s%s%s\n", f.key, value->c_str(),
                  *f.unit && !v->is_null() ? " " : "", v->is_null() ? "" : f.unit);
    out << line;
  }
  if (summary.contains("warnings") && summary["warnings"].is_array() &&
      !summary["warnings"].empty())
  {
    out << "warnings (summary.json):\n";
    for (const auto& w : summary["warnings"])
      if (w.is_string())
        out << "  " << w.get<std::string>() << '\n';
  }
}
} // namespace dembridge::app
