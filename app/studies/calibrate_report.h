#pragma once
// The files of `dembridge calibrate` (calibrate.h): calibration.json's iteration tables, the
// calibrated case files and calibration.png (matplotlib). Internal to calibrate.cc.
#include "app/studies/calibrate_elastic.h"
#include "app/studies/calibrate_strength.h"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace dembridge::app::calibrate_detail
{
nlohmann::json elastic_json(const ElasticCalibration& c, const CalibrationTargets& t);
nlohmann::json strength_json(const StrengthCalibration& c, const CalibrationTargets& t);

/// A case file's text with the overrides ("Section/Sub/key=value") @p given on the command line
/// and @p calibrated written in (the later of two for one key wins): a key the file
/// sets gets the new value on its own line (marked, with the value it had), a key it does not
/// set goes before the end of its subsection, or into a new subsection at the end of the file
/// (a case may open each subsection only once). Comments and layout stay as they were.
std::string overridden_case_text(const std::filesystem::path& case_file,
                                 const std::vector<std::string>& given,
                                 const std::vector<std::string>& calibrated,
                                 const std::string& comment);

/// Writes @p text to dir/name through a temporary file and a rename.
void write_text_atomically(const std::filesystem::path& dir, const std::string& name,
                           const std::string& text);

/// Draws calibration.png from dir/calibration.json; the status for calibration.json:
/// {"file": "calibration.png"} or {"file": null, "error": ...}.
nlohmann::json write_plot(const std::filesystem::path& dir);
} // namespace dembridge::app::calibrate_detail
