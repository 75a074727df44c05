// The elastic calibration: a secant iteration on the stiffness ratio, the modulus scaled in one
// step (calibrate_elastic.h).
#include "app/studies/calibrate_elastic.h"
#include "dem/measurements/measurements.h"
#include "dem/solvers/static_solver.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dembridge::app
{
double voigt_poisson_ratio(double kappa)
{
  return (kappa - 1) / (4 * kappa + 1);
}

double voigt_stiffness_ratio(double nu)
{
  return nu < 0.25 ? (1 + nu) / (1 - 4 * nu) : std::numeric_limits<double>::infinity();
}

namespace
{
/// Timoshenko's Phi of touching spheres (L = 2 R) over lambda^2: 20 (1 + nu_b) / (3 * 4).
double timoshenko_shear_term(const dem::BondMaterial& m)
{
  return m.model == dem::BondModel::timoshenko ? 20 * (1 + m.poisson_ratio) / 9 : 0.0;
}
} // namespace

RatioParameter ratio_parameter_of(const dem::BondMaterial& material)
{
  RatioParameter r;
  r.material = material;
  if (material.model == dem::BondModel::parallel_bond)
    r.key = "stiffness ratio", r.lower = 0.1, r.upper = 100;
  else
    r.key = "radius multiplier", r.lower = 0.05, r.upper = 1;
  return r;
}

double RatioParameter::kappa(double p) const
{
  if (material.model == dem::BondModel::parallel_bond)
    return p;
  return 4 / (3 * p * p) + timoshenko_shear_term(material);
}

double RatioParameter::parameter(double kappa) const
{
  if (material.model == dem::BondModel::parallel_bond)
    return std::clamp(kappa, lower, upper);
  const double bending = kappa - timoshenko_shear_term(material); // 4 / (3 lambda^2)
  if (!(bending > 0))
    return upper;
  return std::clamp(std::sqrt(4 / (3 * bending)), lower, upper);
}

ElasticProbe::ElasticProbe(const dem::CaseConfig& config) : config_(config)
{
  if (config_.measure.modulus_fixed_group.empty())
    throw std::runtime_error("Measurements/modulus groups: calibrate needs the uniaxial test "
                             "(the end groups E and nu are measured between)");
  if (config_.microstructure.enabled())
    throw std::runtime_error("Microstructure: calibrate fits one bond material, and a "
                             "microstructure gives its bond classes their own");
  config_.run.static_solver = true;
  config_.damage.law.mode = dem::FailureMode::none; // the linear, undamaged network
  model_ = dem::build_model(config_);
  fixed_group_ = model_.group_index(config_.measure.modulus_fixed_group, "Measurements");
  loaded_group_ = model_.group_index(config_.measure.modulus_loaded_group, "Measurements");
}

ElasticSample ElasticProbe::measure(double ratio_parameter, double modulus_parameter)
{
  dem::BondMaterial m = config_.bonds.material;
  if (m.model == dem::BondModel::parallel_bond)
    m.stiffness_ratio = ratio_parameter;
  else
    m.radius_multiplier = ratio_parameter;
  if (m.model == dem::BondModel::parallel_bond && m.normal_stiffness_per_area > 0)
    m.normal_stiffness_per_area = modulus_parameter;
  else
    m.youngs_modulus = modulus_parameter;
  auto& p = model_.particles;
  auto& b = model_.bonds;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const auto s = dem::bond_stiffness(m, b.rest_length[k], p.radius[std::size_t(b.a[k])],
                                       p.radius[std::size_t(b.b[k])]);
    b.kn[k] = s.kn, b.ks[k] = s.ks, b.ktor[k] = s.ktor, b.kben[k] = s.kben;
    b.contact_fraction[k] = s.contact_fraction, b.radius[k] = s.radius;
  }
  const dem::StaticResult st = dem::solve_static(model_);
  ++solves_;
  const auto a = dem::axial_response(
      p, model_.groups[std::size_t(fixed_group_)], model_.groups[std::size_t(loaded_group_)],
      config_.measure.modulus_axis, config_.measure.section_area[config_.measure.modulus_axis]);
  ElasticSample s;
  s.ratio_parameter = ratio_parameter;
  s.modulus_parameter = modulus_parameter;
  s.youngs_modulus = a.youngs_modulus;
  int n = 0;
  for (int d = 0; d < 3; ++d)
    if (d != a.axis)
      s.poisson_ratio_lateral[n++] = a.poisson_ratio[d];
  s.poisson_ratio = 0.5 * (s.poisson_ratio_lateral[0] + s.poisson_ratio_lateral[1]);
  s.seconds = st.assembly_seconds + st.solve_seconds;
  if (!(s.youngs_modulus > 0) || !std::isfinite(s.youngs_modulus))
    throw std::runtime_error("Measurements/modulus groups: the uniaxial test measured E = " +
                             std::to_string(s.youngs_modulus) +
                             " Pa (the case must load its end groups apart or together)");
  return s;
}

namespace
{
/// ln kappa of the next sample. The first step scales the Voigt relation by the measured
/// nu / nu_Voigt (the packing's departure from the affine estimate, taken as constant) and
/// solves it for the target; later steps take a secant through the last two samples at
/// distinct ratios (the Voigt slope where a secant does not rise as nu does with kappa).
double next_log_kappa(const std::vector<ElasticSample>& samples, double nu_target)
{
  const ElasticSample& s = samples.back();
  const double x = std::log(s.kappa);
  double slope = 5 * s.kappa / std::pow(4 * s.kappa + 1, 2); // d nu_Voigt / d ln kappa
  bool secant = false;
  for (auto it = samples.rbegin() + 1; it != samples.rend(); ++it)
    if (std::abs(std::log(it->kappa) - x) > 1e-12)
    {
      const double d = (s.poisson_ratio - it->poisson_ratio) / (x - std::log(it->kappa));
      if ((secant = d > 0 && std::isfinite(d)))
        slope = d;
      break;
    }
  double next = x + (nu_target - s.poisson_ratio) / slope;
  const double departure = s.poisson_ratio / voigt_poisson_ratio(s.kappa);
  if (!secant && voigt_poisson_ratio(s.kappa) > 0.01 && departure > 0 &&
      nu_target / departure < 0.25)
    next = std::log(voigt_stiffness_ratio(nu_target / departure));
  // at most a factor 10 in kappa per step: far from the samples the guess is rough
  return std::clamp(next, x - std::log(10.0), x + std::log(10.0));
}

/// The Voigt estimate's E up to a constant, at the modulus parameter 1: k_n (2 kappa + 3) /
/// (4 kappa + 1) with k_n proportional to 1 (parallel bonds) or lambda^2 (beams). The modulus
/// step carries its ratio between two ratio parameters.
double voigt_modulus_shape(const RatioParameter& rp, double parameter)
{
  const double kappa = rp.kappa(parameter);
  const double kn = rp.material.model == dem::BondModel::parallel_bond ? 1 : parameter * parameter;
  return kn * (2 * kappa + 3) / (4 * kappa + 1);
}

std::string out_of_reach(const RatioParameter& rp, const ElasticSample& s, double nu_target,
                         bool above, const std::string& model)
{
  std::ostringstream line;
  line << "Calibration/target poisson ratio: " << nu_target << " is out of reach of " << model
       << " bonds on this packing: the " << (above ? "largest" : "smallest")
       << " Poisson's ratio Bonds/" << rp.key << " gives, at its limit " << s.ratio_parameter
       << ", is " << s.poisson_ratio << " (its range is [" << rp.lower << ", " << rp.upper << "])";
  return line.str();
}
} // namespace

ElasticCalibration calibrate_elastic(ElasticProbe& probe, const dem::BondMaterial& material,
                                     const CalibrationTargets& t, bool progress)
{
  const RatioParameter rp = ratio_parameter_of(material);
  const bool per_area =
      material.model == dem::BondModel::parallel_bond && material.normal_stiffness_per_area > 0;
  ElasticCalibration c;
  c.ratio_key = rp.key;
  c.modulus_key = per_area ? "normal stiffness per area" : "youngs modulus";
  c.ratio_lower = rp.lower, c.ratio_upper = rp.upper;
  c.kappa_start = voigt_stiffness_ratio(t.poisson_ratio);
  const std::string model(dem::bond_model_names[std::size_t(material.model)]);
  double modulus = per_area ? material.normal_stiffness_per_area : material.youngs_modulus;
  double ratio = rp.parameter(c.kappa_start);
  const double nu_scale = std::max(std::abs(t.poisson_ratio), 0.01); // nu_t = 0: absolute
  while (true)
  {
    if (int(c.iterations.size()) >= t.max_static_solves)
    {
      c.failure = "Calibration/max elastic solves: " + std::to_string(t.max_static_solves) +
                  " static solves did not bring E and nu within Calibration/tolerance";
      break;
    }
    ElasticSample s = probe.measure(ratio, modulus);
    s.kappa = rp.kappa(ratio);
    c.iterations.push_back(s);
    c.ratio_parameter = ratio, c.modulus_parameter = modulus;
    if (progress)
      std::printf("calibrate: static solve %zu: %s = %.6g, %s = %.6g: E = %.6g Pa, nu = %.6g "
                  "(%.6g, %.6g)\n",
                  c.iterations.size(), rp.key.c_str(), ratio, c.modulus_key.c_str(), modulus,
                  s.youngs_modulus, s.poisson_ratio, s.poisson_ratio_lateral[0],
                  s.poisson_ratio_lateral[1]);
    std::fflush(stdout);
    const bool e_ok =
        std::abs(s.youngs_modulus - t.youngs_modulus) <= t.elastic_tolerance * t.youngs_modulus;
    const bool nu_ok =
        std::abs(s.poisson_ratio - t.poisson_ratio) <= t.elastic_tolerance * nu_scale;
    if (e_ok && nu_ok)
    {
      c.reached = true;
      break;
    }
    modulus *= t.youngs_modulus / s.youngs_modulus; // exact at a fixed ratio
    if (nu_ok)
      continue;
    const double next = rp.parameter(std::exp(next_log_kappa(c.iterations, t.poisson_ratio)));
    if (next == ratio) // pinned at a limit of the ratio, and the target lies beyond it
    {
      c.failure = out_of_reach(rp, s, t.poisson_ratio, t.poisson_ratio > s.poisson_ratio, model);
      break;
    }
    modulus *= voigt_modulus_shape(rp, ratio) / voigt_modulus_shape(rp, next);
    ratio = next;
  }
  return c;
}
} // namespace dembridge::app
