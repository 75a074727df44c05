#pragma once
// The elastic half of `dembridge calibrate` (calibrate.h): the bond parameters that give a
// packing the target Young's modulus E and Poisson's ratio nu in its uniaxial test.
//
// At a fixed ratio of shear to normal bond stiffness every bond stiffness is proportional to the
// modulus parameter M (Bonds/youngs modulus E_b, or the parallel bond's normal stiffness per
// area), so the specimen's nu does not depend on M and its E is proportional to it:
//   E(kappa, c M) = c E(kappa, M),   nu(kappa, c M) = nu(kappa, M).
// nu is therefore found on the ratio alone, kappa = k_n / k_s, and M follows in one step,
// M <- M E_target / E. The ratio starts at the affine (Voigt) estimate of an isotropic packing
// of normal and shear springs (Liao et al. 1997; the 3-D analogue of Bathurst and Rothenburg
// 1988, and Wang and Mora's (2008) regular-lattice relations in form):
//   nu = (kappa - 1) / (4 kappa + 1),   i.e.   kappa_0 = (1 + nu_t) / (1 - 4 nu_t)   (nu_t < 1/4)
// and is then corrected against the measured nu: the first step solves the Voigt relation scaled
// by the measured nu / nu_Voigt (a packing's departure from the affine estimate changes slowly
// with kappa), later steps are secants on x = ln kappa. When kappa moves, M also carries the
// Voigt estimate's change of E, E_V ~ k_n (2 kappa + 3) / (4 kappa + 1), so that E stays near its
// target while nu converges. Each iteration is one static solve of the case
// (dem/solvers/static_solver.h) that measures both E and nu.
//
// The ratio parameter: parallel bonds, Bonds/stiffness ratio = kappa itself, within [0.1, 100]
// (shear stiffness from 10 k_n down to k_n / 100); beam bonds (Euler-Bernoulli, Timoshenko),
// Bonds/radius multiplier lambda, within [0.05, 1], whose kappa for touching spheres (L = 2 R) is
//   kappa = (4 / (3 lambda^2)) (1 + Phi),   Phi = 5 lambda^2 (1 + nu_b) / 3 (Timoshenko, else 0).
// A target nu beyond the nu the packing gives at the ratio's limit is out of reach.
#include "app/input/calibration_parameters.h"
#include "dem/model/model.h"
#include <string>
#include <vector>

namespace dembridge::app
{
/// One static solve of the iteration.
struct ElasticSample
{
  double ratio_parameter = 0;   ///< the value of ElasticCalibration::ratio_key
  double modulus_parameter = 0; ///< the value of ElasticCalibration::modulus_key
  double kappa = 0;             ///< k_n / k_s it stands for (touching spheres)
  double youngs_modulus = 0;    ///< measured, Pa
  double poisson_ratio = 0;     ///< measured: the mean of the two lateral ratios
  double poisson_ratio_lateral[2] = {0, 0};
  double seconds = 0;
};

/// The packing of a case, built once; each measure() re-stiffens every bond for the given
/// parameters and solves the static uniaxial test (one static solve).
class ElasticProbe
{
public:
  /// Builds the model of @p config (a static uniaxial test: Measurements/modulus groups).
  explicit ElasticProbe(const dem::CaseConfig& config);
  ElasticSample measure(double ratio_parameter, double modulus_parameter);
  int solves() const { return solves_; }
  const dem::Model& model() const { return model_; }

private:
  dem::CaseConfig config_;
  dem::Model model_;
  int fixed_group_ = 0, loaded_group_ = 0, solves_ = 0;
};

struct ElasticCalibration
{
  std::string ratio_key;   ///< "stiffness ratio" | "radius multiplier"
  std::string modulus_key; ///< "youngs modulus" | "normal stiffness per area"
  double ratio_lower = 0, ratio_upper = 0;
  double kappa_start = 0; ///< the Voigt estimate
  std::vector<ElasticSample> iterations;
  bool reached = false;
  /// empty when reached; else the one-line reason (out of reach, or the solve limit)
  std::string failure;
  double ratio_parameter = 0, modulus_parameter = 0; ///< the last sample's (calibrated) values
};

/// The ratio key of a bond material, its range and the map kappa <-> parameter.
struct RatioParameter
{
  std::string key;
  double lower = 0, upper = 0;
  dem::BondMaterial material;
  double kappa(double parameter) const;
  double parameter(double kappa) const; ///< clamped to [lower, upper]
};
RatioParameter ratio_parameter_of(const dem::BondMaterial& material);

/// The Voigt estimate of the packing's nu at kappa, and the kappa that gives @p nu (nu < 1/4;
/// infinite above).
double voigt_poisson_ratio(double kappa);
double voigt_stiffness_ratio(double nu);

/// Runs the iteration from the case's own modulus parameter; @p progress prints each sample.
ElasticCalibration calibrate_elastic(ElasticProbe& probe, const dem::BondMaterial& material,
                                     const CalibrationTargets& targets, bool progress = true);
} // namespace dembridge::app
