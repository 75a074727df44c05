// calibration.json tables, the calibrated case files and calibration.png (calibrate_report.h).
#include "app/studies/calibrate_report.h"
#include "app/studies/verify_report.h"
#include "dem/core/output_file.h"
#include <algorithm>
#include <fstream>
#include <sstream>

namespace dembridge::app::calibrate_detail
{
namespace fs = std::filesystem;
using nlohmann::json;

json elastic_json(const ElasticCalibration& c, const CalibrationTargets& t)
{
  json rows = json::array();
  double seconds = 0;
  for (const auto& s : c.iterations)
  {
    rows.push_back(
        {{c.ratio_key, s.ratio_parameter},
         {c.modulus_key, s.modulus_parameter},
         {"stiffness_ratio_kn_over_ks", s.kappa},
         {"youngs_modulus", s.youngs_modulus},
         {"poisson_ratio", s.poisson_ratio},
         {"poisson_ratio_lateral", {s.poisson_ratio_lateral[0], s.poisson_ratio_lateral[1]}},
         {"solve_seconds", s.seconds}});
    seconds += s.seconds;
  }
  json j = {{"method", "static solves of the uniaxial test: secant on ln(k_n/k_s) for nu from the "
                       "Voigt estimate, the modulus scaled by E_target/E"},
            {"ratio_key", "Bonds/" + c.ratio_key},
            {"ratio_range", {c.ratio_lower, c.ratio_upper}},
            {"modulus_key", "Bonds/" + c.modulus_key},
            {"voigt_start_kn_over_ks", c.kappa_start},
            {"iterations", rows},
            {"static_solves", c.iterations.size()},
            {"solve_seconds", seconds},
            {"reached", c.reached}};
  if (!c.iterations.empty())
  {
    const auto& last = c.iterations.back();
    j["youngs_modulus"] = {{"target", t.youngs_modulus},
                           {"measured", last.youngs_modulus},
                           {"relative_error", last.youngs_modulus / t.youngs_modulus - 1}};
    j["poisson_ratio"] = {{"target", t.poisson_ratio},
                          {"measured", last.poisson_ratio},
                          {"error", last.poisson_ratio - t.poisson_ratio}};
  }
  if (!c.failure.empty())
    j["failure"] = c.failure;
  return j;
}

json strength_json(const StrengthCalibration& c, const CalibrationTargets& t)
{
  json rows = json::array();
  double seconds = 0;
  for (const auto& r : c.iterations)
  {
    rows.push_back({{"strength_factor", r.factor},
                    {"tensile_strength", r.tensile_strength},
                    {"shear_strength", r.shear_strength},
                    {"cohesion", r.cohesion},
                    {"peak_stress", r.peak_stress},
                    {"strain_at_peak", r.strain_at_peak},
                    {"run_seconds", r.seconds}});
    seconds += r.seconds;
  }
  json j = {{"method", "tension runs to failure: secant on the strength factor inside the "
                       "bracket of the runs (bisection when it leaves it)"},
            {"strength_case", c.case_file},
            {"iterations", rows},
            {"tension_runs", c.iterations.size()},
            {"run_seconds", seconds},
            {"reached", c.reached}};
  if (!c.iterations.empty())
    j["tensile_strength"] = {
        {"target", t.tensile_strength},
        {"measured", c.iterations.back().peak_stress},
        {"relative_error", c.iterations.back().peak_stress / t.tensile_strength - 1}};
  if (!c.failure.empty())
    j["failure"] = c.failure;
  return j;
}

namespace
{
struct Setting
{
  std::vector<std::string> path; ///< subsections, outermost first
  std::string key, value;
  std::string note; ///< the end-of-line comment
  bool written = false;
};

std::string trim(const std::string& s)
{
  const auto a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

/// Runs of blanks as one space (deal.II reads "youngs  modulus" as "youngs modulus").
std::string collapse(const std::string& s)
{
  std::string out;
  for (const char c : trim(s))
    if (!(c == ' ' || c == '\t') || (!out.empty() && out.back() != ' '))
      out += (c == '\t' ? ' ' : c);
  return out;
}

void add_settings(std::vector<Setting>& settings, const std::vector<std::string>& overrides,
                  const std::string& note)
{
  for (const std::string& o : overrides)
  {
    Setting s;
    std::stringstream keys(o.substr(0, o.find('=')));
    for (std::string part; std::getline(keys, part, '/');)
      s.path.push_back(collapse(part));
    s.key = s.path.back();
    s.path.pop_back();
    s.value = trim(o.substr(o.find('=') + 1));
    s.note = note;
    // a later override of the same key wins, as with --set
    std::erase_if(settings, [&](const Setting& t) { return t.path == s.path && t.key == s.key; });
    settings.push_back(s);
  }
}

/// The settings of @p path not yet written, as "set" lines at @p indent.
std::string pending_lines(std::vector<Setting>& settings, const std::vector<std::string>& path,
                          const std::string& indent)
{
  std::string out;
  for (Setting& s : settings)
    if (!s.written && s.path == path)
    {
      out += indent + "set " + s.key + " = " + s.value + "  # " + s.note + "\n";
      s.written = true;
    }
  return out;
}
} // namespace

std::string overridden_case_text(const fs::path& case_file, const std::vector<std::string>& given,
                                 const std::vector<std::string>& calibrated,
                                 const std::string& comment)
{
  std::vector<Setting> settings;
  add_settings(settings, given, "--set");
  add_settings(settings, calibrated, "calibrated");
  std::ifstream in(case_file);
  std::string out = "# " + comment + "\n", line;
  std::vector<std::string> path;
  while (std::getline(in, line))
  {
    const std::string code = collapse(line.substr(0, line.find('#')));
    const std::string indent = line.substr(0, line.find_first_not_of(" \t"));
    if (code.rfind("subsection ", 0) == 0)
      path.push_back(collapse(code.substr(11)));
    else if (code == "end" && !path.empty())
    {
      out += pending_lines(settings, path, indent + "  ");
      path.pop_back();
    }
    else if (code.rfind("set ", 0) == 0 && code.find('=') != std::string::npos)
    {
      const std::string key = collapse(code.substr(4, code.find('=') - 4));
      auto it = std::find_if(settings.begin(), settings.end(),
                             [&](const Setting& s)
                             { return !s.written && s.path == path && s.key == key; });
      if (it != settings.end())
      {
        out += indent + "set " + key + " = " + it->value + "  # " + it->note + "; the case had " +
               trim(code.substr(code.find('=') + 1)) + "\n";
        it->written = true;
        continue;
      }
    }
    out += line + "\n";
  }
  // keys of subsections the case does not open: new subsections at the end
  for (Setting& s : settings)
    if (!s.written)
    {
      std::string indent;
      for (const auto& name : s.path)
        out += indent + "subsection " + name + "\n", indent += "  ";
      out += pending_lines(settings, s.path, indent);
      for (std::size_t k = s.path.size(); k-- > 0;)
        out += std::string(2 * k, ' ') + "end\n";
    }
  return out;
}

void write_text_atomically(const fs::path& dir, const std::string& name, const std::string& text)
{
  const fs::path part = dir / (name + ".part");
  {
    dem::OutputFile out(part); // failures name the file and the reason
    out << text;
    out.close();
  }
  fs::rename(part, dir / name);
}

namespace
{
/// Reads calibration.json: E and nu per static solve against their targets (and the tolerance
/// band), and the peak stress per tension run when the strength was calibrated.
constexpr const char* plot_script = R"PY(
import json, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

report, png = sys.argv[1:3]
with open(report) as f:
    j = json.load(f)
t = j["targets"]
panels = [("youngs_modulus", "E (GPa)", 1e-9, "elastic", "static solve"),
          ("poisson_ratio", "Poisson's ratio", 1, "elastic", "static solve")]
if "strength" in j:
    panels.append(("peak_stress", "peak stress (MPa)", 1e-6, "strength", "tension run"))
fig, axes = plt.subplots(1, len(panels), figsize=(4.5 * len(panels), 4))
for ax, (key, label, scale, part, what) in zip(axes, panels):
    rows = j[part]["iterations"]
    y = [scale * r[key] for r in rows]
    ax.plot(range(1, len(y) + 1), y, "o-", label="measured")
    target = scale * t["tensile_strength" if key == "peak_stress" else key]
    tol = t["strength_tolerance" if part == "strength" else "elastic_tolerance"]
    band = tol * (abs(target) if key != "poisson_ratio" else max(abs(target), 0.01 * scale))
    ax.axhline(target, color="k", ls="--", label="target")
    ax.axhspan(target - band, target + band, color="k", alpha=0.1, label="tolerance")
    ax.set_xlabel(what); ax.set_ylabel(label)
    ax.set_xticks(range(1, len(y) + 1)); ax.grid(alpha=0.3); ax.legend()
title = j["targets_file"] + ": " + ("reached" if j["reached"] else "not reached")
if "compression" in j:
    c = j["compression"]
    title += f"; sigma_c / sigma_t = {c['compressive_to_tensile_ratio']:.3g}"
    if "target" in c:
        title += f" (target {c['target']:.3g})"
fig.suptitle(title)
fig.tight_layout()
fig.savefig(png, dpi=110)
)PY";
} // namespace

json write_plot(const fs::path& dir)
{
  const fs::path script = dir / "calibration_plot.py";
  write_text_atomically(dir, script.filename().string(),
                        std::string("# Written by `dembridge calibrate`; usage: python3 "
                                    "calibration_plot.py calibration.json PNG\n") +
                            plot_script);
  return verify_detail::run_plot_script(script, dir / "calibration.json", dir / "calibration.png");
}
} // namespace dembridge::app::calibrate_detail
