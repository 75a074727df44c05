#include "app/input/calibration_parameters.h"
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dembridge::app
{
void declare_calibration_parameters(dealii::ParameterHandler& prm)
{
  namespace P = dealii::Patterns;
  prm.enter_subsection("Calibration");
  prm.declare_entry("target youngs modulus", "0", P::Double(),
                    "`dembridge calibrate`: the specimen's Young's modulus E (Pa) along "
                    "Measurements/modulus axis, reached by scaling the bonds' stiffness.");
  prm.declare_entry("target poisson ratio", "0", P::Double(),
                    "`dembridge calibrate`: the specimen's Poisson's ratio, the mean of the two "
                    "lateral ratios of the uniaxial test, reached through Bonds/stiffness ratio "
                    "(parallel bonds) or Bonds/radius multiplier (beam bonds); in (-1, 0.5).");
  prm.declare_entry("target tensile strength", "0", P::Double(),
                    "`dembridge calibrate`: the peak stress (Pa) of 'strength case'; 0: the "
                    "strengths are not calibrated. Damage/tensile and shear strength (or "
                    "cohesion) scale together, so their ratio stays as given.");
  prm.declare_entry("strength case", "", P::Anything(),
                    "`dembridge calibrate`: the tension-to-failure case (explicit solver, the "
                    "same bond model) whose peak stress is the tensile strength; relative to "
                    "this file. It runs with the calibrated Bonds values.");
  prm.declare_entry("elastic tolerance", "0.001", P::Double(),
                    "Relative tolerance on E and nu: the iteration stops when both are met.");
  prm.declare_entry("strength tolerance", "0.01", P::Double(),
                    "Relative tolerance on the tensile strength.");
  prm.declare_entry("max static solves", "10", P::Integer(1, 100),
                    "Most static solves of the elastic iteration (each gives E and nu).");
  prm.declare_entry("max tension runs", "6", P::Integer(1, 100),
                    "Most tension runs to failure of the strength iteration.");
  prm.leave_subsection();
}

namespace
{
[[noreturn]] void refuse(const std::string& key, double value, const std::string& why)
{
  std::ostringstream s;
  s << "Calibration/" << key << ": " << value << ": " << why;
  throw std::runtime_error(s.str());
}
} // namespace

CalibrationTargets read_calibration_targets(dealii::ParameterHandler& prm)
{
  CalibrationTargets t;
  prm.enter_subsection("Calibration");
  t.youngs_modulus = prm.get_double("target youngs modulus");
  t.poisson_ratio = prm.get_double("target poisson ratio");
  t.tensile_strength = prm.get_double("target tensile strength");
  t.strength_case = prm.get("strength case");
  t.elastic_tolerance = prm.get_double("elastic tolerance");
  t.strength_tolerance = prm.get_double("strength tolerance");
  t.max_static_solves = int(prm.get_integer("max static solves"));
  t.max_tension_runs = int(prm.get_integer("max tension runs"));
  prm.leave_subsection();
  if (!(t.youngs_modulus > 0) || !std::isfinite(t.youngs_modulus))
    refuse("target youngs modulus", t.youngs_modulus,
           "must be positive (a stiffness; the section is needed to calibrate)");
  if (!(t.poisson_ratio > -1 && t.poisson_ratio < 0.5))
    refuse("target poisson ratio", t.poisson_ratio,
           "must lie in (-1, 0.5): an isotropic solid's bulk and shear moduli are positive only "
           "there");
  if (t.tensile_strength < 0 || !std::isfinite(t.tensile_strength))
    refuse("target tensile strength", t.tensile_strength, "must be positive, or 0 for none");
  if (t.tensile_strength > 0 && t.strength_case.empty())
    throw std::runtime_error("Calibration/strength case: empty, and a target tensile strength "
                             "needs the tension-to-failure case that measures it");
  if (t.tensile_strength == 0 && !t.strength_case.empty())
    throw std::runtime_error("Calibration/strength case: '" + t.strength_case +
                             "' given without a target tensile strength to calibrate on it");
  if (t.tensile_strength >= t.youngs_modulus)
    refuse("target tensile strength", t.tensile_strength,
           "contradicts the target Young's modulus (a strength of at least E is a failure "
           "strain of at least 1)");
  if (!(t.elastic_tolerance > 0 && t.elastic_tolerance < 0.5))
    refuse("elastic tolerance", t.elastic_tolerance, "must lie in (0, 0.5)");
  if (!(t.strength_tolerance > 0 && t.strength_tolerance < 0.5))
    refuse("strength tolerance", t.strength_tolerance, "must lie in (0, 0.5)");
  return t;
}
} // namespace dembridge::app
