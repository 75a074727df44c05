#include "app/input/calibration_parameters.h"
#include <cmath>
#include <deal.II/base/utilities.h>
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
  prm.declare_entry("target compressive to tensile ratio", "0", P::Double(),
                    "`dembridge calibrate`: sigma_c / sigma_t, sigma_c the peak stress of "
                    "'compression case' at the calibrated strengths; 0: not a target (the "
                    "ratio is still reported when a compression case is given).");
  prm.declare_entry("strength case", "", P::Anything(),
                    "`dembridge calibrate`: the tension-to-failure case (explicit solver, "
                    "brittle bonds, the same bond model) whose peak stress is the tensile "
                    "strength; relative to this file. It runs with the calibrated Bonds values.");
  prm.declare_entry("compression case", "", P::Anything(),
                    "`dembridge calibrate`: the compression-to-failure case whose peak stress is "
                    "sigma_c; relative to this file. It runs once, with the calibrated Bonds "
                    "and Damage values.");
  prm.declare_entry("spread seeds", "", P::List(P::Integer(0)),
                    "`dembridge calibrate`: Particles/seed values of further packings on which "
                    "the calibrated E and nu are measured (one static solve each) and reported, "
                    "not iterated on: the spread between packings of one kind.");
  prm.declare_entry("spread box size", "", P::Anything(),
                    "`dembridge calibrate`: a Particles/box size (m, 'x, y, z') of a further "
                    "specimen on which E and nu are measured and reported; empty: none.");
  prm.declare_entry("tolerance", "0.005", P::Double(),
                    "Relative tolerance on E and nu: the iteration stops when both are met.");
  prm.declare_entry("strength tolerance", "0.02", P::Double(),
                    "Relative tolerance on the tensile strength and on sigma_c / sigma_t.");
  prm.declare_entry("max elastic solves", "10", P::Integer(1, 100),
                    "Most static solves of the elastic iteration (each gives E and nu).");
  prm.declare_entry("max strength runs", "6", P::Integer(1, 100),
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
  t.compressive_to_tensile_ratio = prm.get_double("target compressive to tensile ratio");
  t.strength_case = prm.get("strength case");
  t.compression_case = prm.get("compression case");
  t.elastic_tolerance = prm.get_double("tolerance");
  for (const std::string& seed : dealii::Utilities::split_string_list(prm.get("spread seeds"), ','))
    t.spread_seeds.push_back(std::stol(seed));
  t.spread_box_size = prm.get("spread box size");
  t.strength_tolerance = prm.get_double("strength tolerance");
  t.max_static_solves = int(prm.get_integer("max elastic solves"));
  t.max_tension_runs = int(prm.get_integer("max strength runs"));
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
  if (t.tensile_strength >= t.youngs_modulus)
    refuse("target tensile strength", t.tensile_strength,
           "contradicts the target Young's modulus (a strength of at least E is a failure "
           "strain of at least 1)");
  if (t.tensile_strength > 0 && t.strength_case.empty())
    throw std::runtime_error("Calibration/strength case: empty, and a target tensile strength "
                             "needs the tension-to-failure case that measures it");
  if (t.tensile_strength == 0 && !t.strength_case.empty())
    throw std::runtime_error("Calibration/strength case: '" + t.strength_case +
                             "' given without a target tensile strength to calibrate on it");
  if (t.compressive_to_tensile_ratio < 0 || !std::isfinite(t.compressive_to_tensile_ratio))
    refuse("target compressive to tensile ratio", t.compressive_to_tensile_ratio,
           "must be positive, or 0 for none");
  if ((t.compressive_to_tensile_ratio > 0 || !t.compression_case.empty()) &&
      t.tensile_strength == 0)
    throw std::runtime_error("Calibration/compression case: sigma_c / sigma_t needs a target "
                             "tensile strength (the strengths it is measured at)");
  if (t.compressive_to_tensile_ratio > 0 && t.compression_case.empty())
    throw std::runtime_error("Calibration/compression case: empty, and a target compressive to "
                             "tensile ratio needs the compression-to-failure case that "
                             "measures it");
  if (!(t.elastic_tolerance > 0 && t.elastic_tolerance < 0.5))
    refuse("tolerance", t.elastic_tolerance, "must lie in (0, 0.5)");
  if (!(t.strength_tolerance > 0 && t.strength_tolerance < 0.5))
    refuse("strength tolerance", t.strength_tolerance, "must lie in (0, 0.5)");
  return t;
}
} // namespace dembridge::app
