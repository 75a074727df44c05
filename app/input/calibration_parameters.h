#pragma once
// The `Calibration` section of a DEM case: the material `dembridge calibrate` fits the bond
// parameters to (app/studies/calibrate.h). Targets of 0 are not calibrated; Young's modulus and
// Poisson's ratio go together (one static solve measures both).
#include <deal.II/base/parameter_handler.h>
#include <string>

namespace dembridge::app
{
struct CalibrationTargets
{
  double youngs_modulus = 0;    ///< E, Pa (required)
  double poisson_ratio = 0;     ///< nu: the mean of the two lateral ratios of the uniaxial test
  double tensile_strength = 0;  ///< sigma_t, Pa; 0: not calibrated
  double elastic_tolerance = 0; ///< relative, on E and nu
  double strength_tolerance = 0;
  int max_static_solves = 0;
  int max_tension_runs = 0;
  /// the tension-to-failure case the strength runs use (as written, relative to the targets
  /// file); empty without a strength target
  std::string strength_case;
};

/// Declares `subsection Calibration`.
void declare_calibration_parameters(dealii::ParameterHandler& prm);

/// Reads and checks the section; throws std::runtime_error "Calibration/<key>: <reason>" for an
/// unphysical or contradictory target.
CalibrationTargets read_calibration_targets(dealii::ParameterHandler& prm);
} // namespace dembridge::app
