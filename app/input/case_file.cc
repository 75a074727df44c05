#include "app/input/case_file.h"
#include "app/input/calibration_parameters.h"
#include "app/input/case_json.h"
#include "app/input/case_scan.h"
#include "app/input/contact_parameters.h"
#include "app/input/dem_parameters.h"
#include "app/input/group_load_parameters.h"
#include "app/input/verification_parameters.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "fem/fem_case.h"
#endif
#ifdef DEMBRIDGE_HAVE_COUPLING
#include "app/input/coupled_parameters.h"
#include "coupling/coupling_parameters.h"
#endif
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace dembridge::app
{
void declare_all_parameters(dealii::ParameterHandler& prm, const std::vector<std::string>& groups,
                            const std::vector<std::string>& loads,
                            const std::vector<std::string>& walls)
{
  prm.declare_entry("Mode", "dem", dealii::Patterns::Selection("dem|fem|coupled"),
                    "dem: bonded-particle model (sections Particles ... Output); fem: deal.II "
                    "continuum (section FEM); coupled: particles in the particle region "
                    "(Particles/origin, box size) tied to the continuum (FEM) through a "
                    "handshake band (section Coupling).");
  declare_dem_parameters(prm);
  declare_group_parameters(prm, groups);
  declare_load_parameters(prm, loads);
  declare_wall_parameters(prm, walls);
  declare_verification_parameters(prm);
  declare_calibration_parameters(prm);
#ifdef DEMBRIDGE_HAVE_FEM
  fem::declare_parameters(prm);
#endif
#ifdef DEMBRIDGE_HAVE_COUPLING
  coupling::declare_coupling_parameters(prm);
#endif
}

std::string one_line(const std::string& what)
{
  std::string s = what;
  const auto info = s.find("Additional information:");
  if (info != std::string::npos)
  {
    s = s.substr(info + 23);
    const auto stack = s.find("Stacktrace:");
    if (stack != std::string::npos)
      s = s.substr(0, stack);
  }
  // drop deal.II's separator lines (runs of dashes), never a value's minus sign
  s = std::regex_replace(s, std::regex("(^|\\n)[ \\t]*-{3,}[ \\t]*(?=\\n|$)"), "\n");
  s = std::regex_replace(s, std::regex("\\s+"), " ");
  const auto b = s.find_first_not_of(' '), e = s.find_last_not_of(' ');
  return b == std::string::npos ? std::string("unknown error") : s.substr(b, e - b + 1);
}

namespace
{
void apply_override(dealii::ParameterHandler& prm, const std::string& text)
{
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw std::runtime_error("--set '" + text + "': no '=value' (expected Section/Key=value)");
  std::string path = text.substr(0, eq), value = text.substr(eq + 1);
  auto trim = [](std::string s)
  {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  path = trim(path);
  value = trim(value);
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t slash; (slash = path.find('/', start)) != std::string::npos; start = slash + 1)
    parts.push_back(trim(path.substr(start, slash - start)));
  const std::string key = trim(path.substr(start));
  if (key.empty())
    throw std::runtime_error("--set '" + text +
                             "': no key before '=' (expected Section/Key=value)");
  auto as_section = parts;
  as_section.push_back(key);
  if (prm.subsection_path_exists(as_section))
    throw std::runtime_error("--set '" + text + "': '" + path +
                             "' is a section, not a key (expected Section/Key=value, e.g. "
                             "'Particles/radius=0.01'; dembridge print-parameters lists the keys)");
  // Reject unknown sections/keys with our own message (deal.II would assert).
  std::string as_prm;
  for (const auto& s : parts)
    as_prm += "subsection " + s + "\n";
  as_prm += "set " + key + " = " + value + "\n";
  for (std::size_t i = 0; i < parts.size(); ++i)
    as_prm += "end\n";
  try
  {
    prm.parse_input_from_string(as_prm, "", false);
  }
  catch (const std::exception& e)
  {
    const std::string msg =
        std::regex_replace(one_line(e.what()), std::regex("Line <\\d+> of file <[^>]*>: "), "");
    throw std::runtime_error("--set " + path + ": " + msg);
  }
}

/// Parses the case: .prm text from memory (@p text), JSON from its tree (case_json.h), .xml
/// from the file.
void parse_file(dealii::ParameterHandler& prm, const std::string& file, const std::string& text,
                const JsonCase* json, const std::vector<std::string>& overrides,
                bool skip_undefined)
{
  try
  {
    const auto ext = std::filesystem::path(file).extension();
    if (json)
      set_json_case(prm, *json, file, skip_undefined);
    else if (ext == ".xml")
      prm.parse_input(file, "", skip_undefined, false);
    else
    {
      std::istringstream in(text);
      prm.parse_input(in, file, "", skip_undefined);
    }
  }
  catch (const std::exception& e)
  {
    std::string msg = one_line(e.what());
    if (msg.find(file) == std::string::npos)
      msg = file + ": " + msg;
    throw std::runtime_error(msg);
  }
  for (const auto& o : overrides)
    apply_override(prm, o);
}

/// A name listed twice would declare its subsection twice (deal.II: "no such subsection" for
/// the one the user meant).
void check_unique_names(const std::vector<std::string>& names, const std::string& list)
{
  std::set<std::string> seen;
  for (const auto& n : names)
    if (!seen.insert(n).second)
      throw std::runtime_error(list + ": '" + n + "' is listed twice");
}

/// A `subsection Group NAME` (Load, Wall) whose name its list does not hold: deal.II would
/// only say that there is no such subsection.
void check_subsections_listed(const CaseScan& scan, const std::vector<std::string>& names,
                              const std::string& prefix, const std::string& list,
                              const std::string& file)
{
  for (const auto& section : scan.subsections)
  {
    if (section.rfind(prefix + " ", 0) != 0 || section.find('/') != std::string::npos)
      continue;
    const std::string name = section.substr(prefix.size() + 1);
    if (std::find(names.begin(), names.end(), name) != names.end())
      continue;
    std::string listed;
    for (const auto& n : names)
      listed += (listed.empty() ? "" : ", ") + n;
    throw std::runtime_error(file + ": subsection '" + section + "' is not named in " + list +
                             (listed.empty() ? " (it is empty)" : " (" + listed + ")"));
  }
}

/// A UTF-8 byte-order mark (some editors write one) is not part of the first line.
std::string without_byte_order_mark(const std::string& text)
{
  return text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text;
}
} // namespace

std::unique_ptr<dealii::ParameterHandler> read_case(const std::string& file,
                                                    const std::vector<std::string>& overrides)
{
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw std::runtime_error(file + ": is a directory, not a case file (give the .prm or .json "
                                    "file)");
  if (!std::filesystem::exists(file, ec))
    throw std::runtime_error(file + ": no such case file");
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error(file + ": is not a regular file (give the .prm or .json file)");
  std::ifstream probe(file);
  if (!probe)
    throw std::runtime_error(file + ": cannot read the case file");
  const std::string text((std::istreambuf_iterator<char>(probe)), std::istreambuf_iterator<char>());
  return read_case_text(text, file, overrides);
}

std::unique_ptr<dealii::ParameterHandler> read_case_text(const std::string& raw_text,
                                                         const std::string& file,
                                                         const std::vector<std::string>& overrides)
{
  const std::string text = without_byte_order_mark(raw_text);
  // what deal.II would accept silently: an empty file, a key or subsection given twice
  CaseScan scan;
  std::unique_ptr<JsonCase> json;
  const auto ext = std::filesystem::path(file).extension();
  if (ext != ".json" && ext != ".xml")
    scan = scan_case_text(text, file);
  else if (text.find_first_not_of(" \t\r\n{}") == std::string::npos)
    throw std::runtime_error(file + ": the case file sets no parameter");
  else if (ext == ".json")
  {
    json = std::make_unique<JsonCase>(parse_json_case(text, file));
    scan = json->scan;
  }
  // Pass 1: only to learn the group, load and wall names.
  dealii::ParameterHandler first;
  declare_all_parameters(first);
  parse_file(first, file, text, json.get(), {}, true);
  for (const auto& o : overrides)
    if (o.rfind("Groups/names", 0) == 0 || o.rfind("Loads/names", 0) == 0 ||
        o.rfind("Walls/names", 0) == 0)
      apply_override(first, o);
  const auto groups = split_names(first.get({"Groups"}, "names"));
  const auto loads = split_names(first.get({"Loads"}, "names"));
  const auto walls = split_names(first.get({"Walls"}, "names"));
  check_unique_names(groups, file + ": Groups/names");
  check_unique_names(loads, file + ": Loads/names");
  check_unique_names(walls, file + ": Walls/names");
  if (!scan.subsections.empty() || scan.entries > 0)
  {
    check_named_subsections(scan, overrides, groups, file + ": Groups/names", "Group");
    check_named_subsections(scan, overrides, loads, file + ": Loads/names", "Load");
    check_subsections_listed(scan, groups, "Group", "Groups/names", file);
    check_subsections_listed(scan, loads, "Load", "Loads/names", file);
    check_subsections_listed(scan, walls, "Wall", "Walls/names", file);
  }
  // Pass 2: strict, with every named subsection declared.
  auto prm = std::make_unique<dealii::ParameterHandler>();
  declare_all_parameters(*prm, groups, loads, walls);
  parse_file(*prm, file, text, json.get(), overrides, false);
  return prm;
}
} // namespace dembridge::app
