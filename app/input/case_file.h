#pragma once
// Reading a case file (.prm, or .json: case_json.h): every parameter of every mode is declared
// (unknown keys are errors), `Groups/names`, `Loads/names` and `Walls/names` add their named
// subsections (two passes; a name listed twice, or a named subsection no list names, is
// refused), `--set` overrides are applied after the file, and deal.II's multi-line parser
// messages are folded into one line that names the file.
#include <deal.II/base/parameter_handler.h>
#include <memory>
#include <string>
#include <vector>

namespace dembridge::app
{
/// Declares the top-level entry `Mode` and every module's subsections.
void declare_all_parameters(dealii::ParameterHandler& prm,
                            const std::vector<std::string>& group_names = {},
                            const std::vector<std::string>& load_names = {},
                            const std::vector<std::string>& wall_names = {});

/// Parses `file` plus the `Section/Key=value` overrides; throws std::runtime_error with a
/// one-line message naming the file (or override) and the reason.
std::unique_ptr<dealii::ParameterHandler> read_case(const std::string& file,
                                                    const std::vector<std::string>& overrides);
/// The same for the text of a case file; @p file names it in messages and decides the format
/// by its extension (.xml is read from the file itself). The fuzz target's entry.
std::unique_ptr<dealii::ParameterHandler> read_case_text(const std::string& text,
                                                         const std::string& file,
                                                         const std::vector<std::string>& overrides);

/// Folds a deal.II exception text into one line (its "Additional information" part).
std::string one_line(const std::string& what);
} // namespace dembridge::app
