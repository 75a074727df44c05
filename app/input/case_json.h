#pragma once
// JSON case files, read with nlohmann-json and set entry by entry into deal.II's
// ParameterHandler, so that they get the .prm path's checks: two passes for the named
// subsections (Group/Load/Wall NAME), a key given twice refused (JSON parsers keep the last),
// messages that name the key. The form is deal.II's own print_parameters(ShortJSON) output, the
// `parameters` object of summary.json:
//   {"Mode": "dem", "Particles": {"radius": "0.1", "count": 11}, "Load tip": {...}}
// Values are strings, numbers (their text as written) or true/false; an entry may also be
// deal.II's long form {"value": "0.1", "documentation": ...} (print_parameters(JSON)).
#include "app/input/case_scan.h"
#include <deal.II/base/parameter_handler.h>
#include <nlohmann/json.hpp>
#include <string>

namespace dembridge::app
{
struct JsonCase
{
  nlohmann::ordered_json tree; ///< every value a string, in the file's order
  CaseScan scan;               ///< top-level subsections and the number of values
};

/// Parses the text of a JSON case; throws std::runtime_error naming @p file (and the line) for
/// malformed JSON, comments (JSON has none), a key given twice in one object, lists and nulls.
JsonCase parse_json_case(const std::string& text, const std::string& file);

/// Sets every entry of @p json into @p prm. @p skip_undefined: entries and subsections @p prm
/// does not declare are passed over (the first pass, which only learns the names); otherwise
/// they are refused naming the file and the key, as are values that do not match their pattern.
void set_json_case(dealii::ParameterHandler& prm, const JsonCase& json, const std::string& file,
                   bool skip_undefined);
} // namespace dembridge::app
