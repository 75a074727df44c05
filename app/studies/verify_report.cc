// dembridge verify: comparison.csv and comparison.png (see verify_report.h).
#include "app/studies/verify_report.h"
#include "dem/core/output_file.h"
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>

namespace dembridge::app::verify_detail
{
namespace fs = std::filesystem;
using nlohmann::json;

namespace
{
// The plot: left, the relative differences of the scalar quantities (values in the labels); right,
// the layer-averaged normal stress through the depth, DEM slab averages and FE averages.
constexpr const char* plot_script = R"PY(
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
src, dst, title = sys.argv[1], sys.argv[2], sys.argv[3]
scalars, layers = [], []
with open(src) as f:
    for r in csv.DictReader(f):
        (layers if r["kind"] == "layer" else scalars).append(r)
num = lambda s: float(s) if s not in ("", None) else None
fig, (a, b) = plt.subplots(1, 2, figsize=(13, 5.5), gridspec_kw={"width_ratios": [1.25, 1]})
names, diffs, labels = [], [], []
for r in scalars:
    d, e, rel = num(r["dem"]), num(r["fem"]), num(r["relative_difference"])
    names.append(r["quantity"])
    diffs.append(100 * rel if rel is not None else float("nan"))
    labels.append("DEM %s, FE %s %s" % ("%.4g" % d if d is not None else "-",
                                         "%.4g" % e if e is not None else "-", r["unit"]))
y = list(range(len(names)))
a.barh(y, diffs, color=["tab:red" if abs(v) > 1 else "tab:green" for v in diffs])
a.axvline(0.0, color="k", lw=0.8)
for k, v in enumerate(diffs):
    if v == v:
        a.annotate("%+.3g %%" % v, (v, k), xytext=(3 if v >= 0 else -3, 0),
                   textcoords="offset points", va="center", ha="left" if v >= 0 else "right",
                   fontsize=7)
a.set_yticks(y)
a.set_yticklabels(["%s\n%s" % (n, l) for n, l in zip(names, labels)], fontsize=7)
a.invert_yaxis()
a.set_xlabel("(FE - DEM) / |DEM|  (%)")
a.set_title("quantities (green: within 1 %)")
lim = max([abs(v) for v in diffs if v == v] + [1.0]) * 1.3
a.set_xlim(-lim, lim)
if layers:
    z = [num(r["position"]) for r in layers]
    dem = [num(r["dem"]) for r in layers]
    fem = [num(r["fem"]) for r in layers]
    if any(v is not None for v in dem):
        b.plot([v / 1e6 if v is not None else float("nan") for v in dem], z, "o",
               label="DEM (eq. 54 slab averages)")
    b.plot([v / 1e6 for v in fem], z, "s-", mfc="none", label="FE (same slabs)")
    b.set_xlabel("%s (MPa)" % layers[0]["quantity"].split("_", 2)[2])
    b.set_ylabel("%s (m), slab centre" % layers[0]["axis"])
    b.axvline(0.0, color="k", lw=0.5)
    b.legend(fontsize=8)
    b.set_title("layer-averaged normal stress")
fig.suptitle(title, fontsize=10)
fig.tight_layout()
fig.savefig(dst, dpi=120)
)PY";

std::string csv_number(double v)
{
  std::ostringstream s;
  s << std::setprecision(12) << v;
  return s.str();
}

std::string last_line(const fs::path& file)
{
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty())
      last = line;
  return last;
}
} // namespace

std::string python()
{
  if (const char* env = std::getenv("DEMBRIDGE_PYTHON"); env && *env)
    return env;
  if (fs::exists("/usr/bin/python3"))
    return "/usr/bin/python3";
  return "python3";
}

std::string shell_quote(const std::string& s)
{
  std::string q = "'";
  for (const char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

json run_plot_script(const fs::path& script, const fs::path& input, const fs::path& png,
                     const std::vector<std::string>& extra)
{
  const fs::path log = fs::path(script).replace_extension(".log");
  const fs::path png_tmp = fs::path(png).replace_extension(".part.png");
  std::string command = shell_quote(python()) + " " + shell_quote(script.string()) + " " +
                        shell_quote(input.string()) + " " + shell_quote(png_tmp.string());
  for (const std::string& arg : extra)
    command += " " + shell_quote(arg);
  command += " > " + shell_quote(log.string()) + " 2>&1";
  const int code = std::system(command.c_str());
  const int rc = WIFEXITED(code) ? WEXITSTATUS(code) : code;
  json status = {{"file", nullptr}};
  if (rc == 0 && fs::is_regular_file(png_tmp))
  {
    fs::rename(png_tmp, png);
    fs::remove(log);
    status["file"] = png.filename().string();
  }
  else
  {
    fs::remove(png_tmp);
    const std::string why = last_line(log);
    status["error"] = python() + " failed (exit " + std::to_string(rc) +
                      (why.empty() ? std::string(")") : "): " + why) + "; see " +
                      log.filename().string();
  }
  return status;
}

json row_json(const Row& row)
{
  json j;
  j["unit"] = row.unit;
  j["dem"] = row.dem ? json(*row.dem) : json(nullptr);
  j["fem"] = row.fem ? json(*row.fem) : json(nullptr);
  if (row.dem && row.fem)
  {
    j["difference"] = *row.fem - *row.dem;
    j["relative_difference"] =
        *row.dem != 0 ? json((*row.fem - *row.dem) / std::abs(*row.dem)) : json(nullptr);
  }
  else
    j["difference"] = j["relative_difference"] = nullptr;
  if (row.position)
    j["position"] = *row.position;
  if (!row.note.empty())
    j["note"] = row.note;
  return j;
}

void write_json_atomically(const fs::path& dir, const std::string& name, const json& j)
{
  const fs::path tmp = dir / (name + ".part");
  {
    dem::OutputFile out(tmp); // failures name the file and the reason
    out << j.dump(2) << '\n';
    out.close();
  }
  fs::rename(tmp, dir / name);
}

json write_table_and_plot(const Report& report, const fs::path& dir, const std::string& title,
                          const bool plot)
{
  const fs::path csv = dir / "comparison.csv", csv_tmp = dir / "comparison.csv.part";
  {
    dem::OutputFile out(csv_tmp); // failures name the file and the reason
    out << "kind,quantity,unit,axis,position,dem,fem,difference,relative_difference\n";
    auto cell = [](const json& v)
    { return v.is_number() ? csv_number(v.get<double>()) : std::string(); };
    for (const auto* rows : {&report.scalars, &report.layers})
      for (const auto& row : *rows)
      {
        const json j = row_json(row);
        const bool layer = row.position.has_value();
        out << (layer ? "layer" : "scalar") << ',' << row.key << ',' << row.unit << ','
            << (layer ? report.layer_axis : "") << ',' << (layer ? csv_number(*row.position) : "")
            << ',' << cell(j["dem"]) << ',' << cell(j["fem"]) << ',' << cell(j["difference"]) << ','
            << cell(j["relative_difference"]) << '\n';
      }
    out.close();
  }
  fs::rename(csv_tmp, csv);

  json status = {{"file", nullptr}};
  if (!plot)
  {
    status["error"] = "disabled (--no-plot)";
    return status;
  }
  const fs::path script = dir / "comparison_plot.py";
  {
    std::ofstream out(script);
    out << "# Written by `dembridge verify`; usage: python3 comparison_plot.py CSV PNG TITLE\n"
        << plot_script;
  }
  return run_plot_script(script, csv, dir / "comparison.png", {title});
}

std::string num(double v)
{
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}
} // namespace dembridge::app::verify_detail
