#pragma once
// dembridge verify, the report half: the side-by-side table (summary.json entries, comparison.csv)
// and the plot (comparison.png, matplotlib). Internal to app/verify.cc.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace dembridge::app::verify_detail
{
/// One compared quantity; difference = fem - dem, relative_difference = difference / |dem|.
struct Row
{
  std::string key;  ///< snake_case name (summary.json, CSV)
  std::string unit; ///< SI
  std::optional<double> dem, fem;
  std::optional<double> position; ///< layer centre (m) for layer rows
  std::string note;
};

struct Report
{
  std::vector<Row> scalars;
  std::vector<Row> layers;     ///< the compared normal stress per slab, bottom to top
  std::string layer_axis;      ///< "x" | "y" | "z"
  std::string layer_component; ///< e.g. "sigma_xx"
  std::vector<double> layer_edges;
};

/// The JSON object of one row.
nlohmann::json row_json(const Row& row);

/// Writes D/comparison.csv (atomically) and, if @p plot, D/comparison.png through python3 with
/// matplotlib (DEMBRIDGE_PYTHON, else /usr/bin/python3, else python3 from PATH). Returns the
/// plot status for summary.json: {"file": "comparison.png"} or {"file": null, "error": ...}.
nlohmann::json write_table_and_plot(const Report& report, const std::filesystem::path& dir,
                                    const std::string& title, bool plot);

/// The interpreter for plot scripts: DEMBRIDGE_PYTHON, else /usr/bin/python3 (Debian's, with
/// matplotlib), else python3 from PATH.
std::string python();
/// @p s single-quoted for a POSIX shell.
std::string shell_quote(const std::string& s);

/// Runs `python() SCRIPT INPUT PNG.part.png EXTRA...` (its output in SCRIPT's .log beside it) and
/// moves the picture to @p png when the script succeeds. Returns the plot status for
/// summary.json: {"file": PNG's name} or {"file": null, "error": the interpreter's exit code and
/// last line, and the log's name}.
nlohmann::json run_plot_script(const std::filesystem::path& script,
                               const std::filesystem::path& input, const std::filesystem::path& png,
                               const std::vector<std::string>& extra = {});

/// Round-trip text of a double (17 significant digits).
std::string num(double v);

/// Writes @p j to dir/name through a temporary file and a rename.
void write_json_atomically(const std::filesystem::path& dir, const std::string& name,
                           const nlohmann::json& j);
} // namespace dembridge::app::verify_detail
