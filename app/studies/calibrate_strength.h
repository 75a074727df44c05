#pragma once
// The strength half of `dembridge calibrate` (calibrate.h): the bond strengths that give the
// tension-to-failure case (Calibration/strength case) the target peak stress sigma_t.
//
// With brittle bonds and a fixed stiffness, scaling every strength by one factor s scales a
// quasi-static failure exactly: each bond breaks at s times its strain, the sequence of breaks
// is the same, and the load-displacement curve is the same curve stretched by s in both
// directions, so the peak stress is s sigma_peak(1). An explicit run at a fixed loading rate is
// nearly so (the rate is relatively slower at larger s). The factor is found by a secant
// iteration on peak(s), started from the proportional step s_1 = s_0 sigma_t / sigma_peak(s_0)
// and kept inside the bracket the runs have established (bisection when the secant leaves it).
// Damage/tensile strength, shear strength and cohesion scale together: their ratios, and with
// them the specimen's failure mode, stay as the case gives them.
#include "app/input/calibration_parameters.h"
#include <filesystem>
#include <string>
#include <vector>

namespace dembridge::app
{
struct StrengthSample
{
  double factor = 1;           ///< on the strength case's own strengths
  double tensile_strength = 0; ///< Damage/tensile strength of the run, Pa
  double shear_strength = 0;   ///< Damage/shear strength, Pa
  double cohesion = 0;         ///< Damage/cohesion, Pa
  double peak_stress = 0;      ///< measured, Pa
  double strain_at_peak = 0;
  double seconds = 0;
};

struct StrengthCalibration
{
  std::string case_file; ///< as Calibration/strength case names it
  std::vector<StrengthSample> iterations;
  bool reached = false;
  std::string failure; ///< empty when reached
  /// the overrides of the last run: the calibrated Bonds values and the scaled strengths
  std::vector<std::string> overrides;
};

/// Runs the iteration on @p strength_case with @p bond_overrides ("Bonds/key=value") applied
/// to every run; each run's output goes to @p scratch (removed afterwards). Throws
/// std::runtime_error "<case>: <key>: <reason>" when the case cannot measure a strength.
StrengthCalibration calibrate_strength(const std::filesystem::path& strength_case,
                                       const std::vector<std::string>& bond_overrides,
                                       const std::string& bond_model,
                                       const CalibrationTargets& targets,
                                       const std::filesystem::path& scratch, bool progress = true);

/// Reads the strength and compression cases (either path may be empty) and checks that they can
/// measure what they are for, before any solve: throws std::runtime_error "<case>: <key>:
/// <reason>".
void check_failure_cases(const std::filesystem::path& strength_case,
                         const std::filesystem::path& compression_case,
                         const std::string& bond_model);

/// sigma_c / sigma_t: one compression run to failure at the calibrated strengths. Scaling every
/// strength by one factor leaves the ratio unchanged, so it is measured and compared with the
/// target, not iterated on.
struct CompressionResult
{
  std::string case_file;
  double peak_stress = 0; ///< sigma_c, Pa
  double ratio = 0;       ///< sigma_c / sigma_t
  double seconds = 0;
  bool reached = true; ///< no target, or the target within the strength tolerance
  std::string failure; ///< the one line when the target is out of reach
};
CompressionResult measure_compression(const std::filesystem::path& compression_case,
                                      const std::vector<std::string>& calibrated_overrides,
                                      double tensile_strength, const CalibrationTargets& targets,
                                      const std::string& bond_model,
                                      const std::filesystem::path& scratch);
} // namespace dembridge::app
