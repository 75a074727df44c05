#pragma once
// The `Calibration` section of a DEM case: the material `dembridge calibrate` fits the bond
// parameters to (app/studies/calibrate.h). Young's modulus and Poisson's ratio are required and
// go together (one static solve measures both); the tensile strength and the ratio of
// compressive to tensile strength are optional (0: not calibrated).
#include <deal.II/base/parameter_handler.h>
#include <string>
#include <vector>

namespace dembridge::app
{
struct CalibrationTargets
{
  double youngs_modulus = 0;   ///< E, Pa (required)
  double poisson_ratio = 0;    ///< nu: the mean of the two lateral ratios of the uniaxial test
  double tensile_strength = 0; ///< sigma_t, Pa; 0: not calibrated
  double compressive_to_tensile_ratio = 0; ///< sigma_c / sigma_t; 0: not a target
  double elastic_tolerance = 0;            ///< relative, on E and nu (Calibration/tolerance)
  double strength_tolerance = 0;           ///< relative, on sigma_t and sigma_c / sigma_t
  int max_static_solves = 0;
  int max_tension_runs = 0;
  /// the tension-to-failure case the strength runs use (as written, relative to the targets
  /// file); empty without a strength target
  std::string strength_case;
  /// the compression-to-failure case that measures sigma_c (as written); empty: none
  std::string compression_case;
  /// The calibrated elastic parameters checked on other packings of the same kind, reported
  /// and not iterated on: one packing per seed (Particles/seed), and one of this box size
  /// (Particles/box size, as written; empty: none).
  std::vector<long> spread_seeds;
  std::string spread_box_size;
};

/// Declares `subsection Calibration`.
void declare_calibration_parameters(dealii::ParameterHandler& prm);

/// Reads and checks the section; throws std::runtime_error "Calibration/<key>: <reason>" for an
/// unphysical or contradictory target.
CalibrationTargets read_calibration_targets(dealii::ParameterHandler& prm);
} // namespace dembridge::app
