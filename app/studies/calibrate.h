#pragma once
// dembridge calibrate TARGETS.prm: the bond parameters that give a packing a target material.
// TARGETS.prm is an ordinary DEM case (packing, bonds, a static uniaxial test between
// Measurements/modulus groups) with a `Calibration` section (app/input/calibration_parameters.h):
// target E and nu, optionally a target tensile strength and the tension-to-failure case that
// measures it, and a compression-to-failure case for sigma_c / sigma_t. The elastic half
// (calibrate_elastic.h) finds the stiffness ratio (or the beam bonds' radius multiplier) and the
// modulus on the static solver; the strength half (calibrate_strength.h) scales the Damage
// strengths of the tension case, which runs with the calibrated Bonds values; the compression
// case runs once at the calibrated strengths (the ratio is measured, not iterated on). The
// calibrated values are also measured on the packings of Calibration/spread seeds and spread box
// size (reported, not iterated on). Writes into the output folder D:
//   D/calibration.json   targets, each iteration's parameters and measured values, run counts,
//                        wall time, the spread, reached or not, the calibrated values
//   D/calibration.png    each iteration's E, nu (and peak stress) against the targets
//   D/calibrated.prm     TARGETS.prm with the calibrated Bonds values (runs with dembridge run)
//   D/calibrated_strength.prm  the strength case with the calibrated Bonds and Damage values
// The calibrated files are written when E, nu (and sigma_t) are reached; calibration.json
// always, with the reason when a target is not (out of reach of the bond model, or the run
// limits). A sigma_c / sigma_t target out of reach leaves the calibrated files written and the
// command failing with its reason.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace dembridge::app
{
struct CalibrateOptions
{
  std::string targets_file;
  std::vector<std::string> overrides; ///< --set "Section/Key=value", on TARGETS.prm
  std::string output_dir;             ///< empty: output/calibrate_<targets stem>
  bool plot = true;
  bool progress = true; ///< print each solve and run
};

struct CalibrationResult
{
  nlohmann::json report; ///< calibration.json
  bool reached = false;
  std::string failure; ///< the one-line reason when a target was not reached
  std::filesystem::path output_dir;
};

/// Reads and checks the targets (std::runtime_error "<file>: <Section/key>: <reason>" before
/// anything is written), calibrates and writes the output folder.
CalibrationResult calibrate(const CalibrateOptions& options);

/// The command: calibrate, print the calibrated values; exit code 1 with the reason on stderr
/// when a target is out of reach.
int run_calibrate(const CalibrateOptions& options);
} // namespace dembridge::app
