#pragma once
// What produced a results folder: the version and git commit of the binary, the command line,
// the host, the threads and the complete effective parameter set (after --set), recorded in
// summary.json and written as parameters.prm, a case file that reruns the case as it ran.
// Also the short table of measured figures that `run` prints at its end.
#include <deal.II/base/parameter_handler.h>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace dembridge::app
{
/// Remembers the command line (main calls this once, before parsing).
void set_command_line(int argc, const char* const* argv);
/// The command line as typed, one element per argument.
const std::vector<std::string>& command_line();

/// Every parameter of @p prm with its effective value, nested by subsection:
/// {"Mode": "dem", "Particles": {"radius": "0.005", ...}, ...}; values as the case file spells
/// them (strings).
nlohmann::json parameters_json(const dealii::ParameterHandler& prm);

/// The effective parameter set as a case file (deal.II's short PRM form, every entry), with
/// relative file paths (Particles/file, Particles/save file, FEM/Mesh/file) resolved against
/// @p case_dir, so that the file reruns the case from any folder.
std::string parameters_file_text(const dealii::ParameterHandler& prm,
                                 const std::filesystem::path& case_dir,
                                 const std::string& header);

/// Writes parameters_file_text to @p file, headed by a comment naming the version, the commit
/// and the case it was made from.
void write_parameters_file(const dealii::ParameterHandler& prm,
                           const std::filesystem::path& case_file,
                           const std::filesystem::path& file);

/// {"version", "git_commit", "command_line", "host", "threads", "started_at", "parameters"}.
nlohmann::json provenance(const dealii::ParameterHandler& prm, const std::string& started_at);

/// Current UTC time as ISO 8601 (2026-12-01T10:24:04Z).
std::string utc_now();

/// Prints the figures the case measured (deflections, E, nu, frequency, a failure run's peak and
/// broken bonds, energy balance error, ...) that @p summary holds, one per line: name, value,
/// unit ("undefined" for a null figure), then the summary's warnings.
void print_figures(const nlohmann::json& summary, std::ostream& out);
} // namespace dembridge::app
