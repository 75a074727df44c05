// The strength calibration: a bracketed secant on the strength factor (calibrate_strength.h).
#include "app/studies/calibrate_strength.h"
#include "app/input/case_file.h"
#include "app/runs/dem_run.h"
#include "app/studies/verify.h"
#include "app/studies/verify_report.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dembridge::app
{
namespace fs = std::filesystem;

namespace
{
/// The strength case's own strengths (the factor 1), checked to be a tension run to failure.
struct BaseStrengths
{
  double tensile = 0, shear = 0, cohesion = 0;
};

BaseStrengths read_base(dealii::ParameterHandler& prm, const std::string& name,
                        const std::string& bond_model)
{
  auto fail = [&](const std::string& why) { throw std::runtime_error(name + ": " + why); };
  if (prm.get("Mode") != "dem")
    fail("Mode: the strength case must be a DEM case (Mode = dem)");
  if (prm.get({"Simulation"}, "solver") != "explicit")
    fail("Simulation/solver: the strength case runs to failure, which needs the explicit solver");
  if (prm.get({"Damage"}, "failure") != "brittle")
    fail("Damage/failure: the strengths scale the peak exactly for brittle bonds only (got '" +
         prm.get({"Damage"}, "failure") + "')");
  if (prm.get({"Measurements"}, "modulus groups").empty())
    fail("Measurements/modulus groups: the peak stress is measured between the end groups");
  if (prm.get({"Bonds"}, "model") != bond_model)
    fail("Bonds/model: '" + prm.get({"Bonds"}, "model") + "', and the elastic case calibrates '" +
         bond_model + "' bonds");
  BaseStrengths b;
  b.tensile = prm.get_double({"Damage"}, "tensile strength");
  b.shear = prm.get_double({"Damage"}, "shear strength");
  b.cohesion = prm.get_double({"Damage"}, "cohesion");
  if (!(b.tensile > 0))
    fail("Damage/tensile strength: must be positive (it is the strength the factor scales)");
  return b;
}

/// The compression case: an explicit run to failure of the calibrated bond model.
void check_compression_case(dealii::ParameterHandler& prm, const std::string& name,
                            const std::string& bond_model)
{
  if (prm.get("Mode") != "dem")
    throw std::runtime_error(name + ": Mode: the compression case must be a DEM case");
  if (prm.get({"Simulation"}, "solver") != "explicit")
    throw std::runtime_error(name + ": Simulation/solver: the compression case runs to "
                                    "failure, which needs the explicit solver");
  if (prm.get({"Bonds"}, "model") != bond_model)
    throw std::runtime_error(name + ": Bonds/model: '" + prm.get({"Bonds"}, "model") +
                             "', and the elastic case calibrates '" + bond_model + "' bonds");
}

std::string set(const std::string& key, double value)
{
  return key + "=" + verify_detail::num(value);
}

/// Runs @p file with @p overrides into @p dir; its peak stress, checked to be past the peak
/// when the run ended (a failure, not a load cut short).
StrengthSample run_to_failure(const fs::path& file, const std::vector<std::string>& overrides,
                              const fs::path& dir)
{
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> run_overrides = overrides;
  run_overrides.push_back("Output/write vtu=false"); // only the summary is read
  auto prm = read_case(file.string(), run_overrides);
  fs::create_directories(dir);
  nlohmann::json summary;
  {
    WorkingDirectory cd(fs::absolute(file).parent_path());
    summary = run_dem_case(*prm, fs::absolute(dir));
  }
  const std::string name = file.filename().string();
  if (!summary.contains("peak_stress") || !summary["peak_stress"].is_number())
    throw std::runtime_error(name + ": Measurements: the run measured no peak stress (a tension "
                                    "case needs Measurements/modulus groups and a load history, "
                                    "a compression case platens)");
  StrengthSample r;
  r.peak_stress = summary["peak_stress"].get<double>();
  r.strain_at_peak = summary.value("strain_at_peak", 0.0);
  // the end load (tension between end groups) or the platen stress, over the peak
  double final_to_peak = summary.value("final_to_peak_load", 1.0);
  if (!summary.contains("final_to_peak_load") && summary.contains("final_stress"))
    final_to_peak = summary["final_stress"].get<double>() / r.peak_stress;
  if (!(std::abs(final_to_peak) < 0.9))
    throw std::runtime_error(name +
                             ": Simulation/end time: the specimen had not failed when the "
                             "run ended (final load " +
                             verify_detail::num(final_to_peak) + " of the peak); load it further");
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

/// One tension run at strength factor @p s; its peak stress.
StrengthSample run_once(const fs::path& file, const std::vector<std::string>& bond_overrides,
                        const BaseStrengths& base, double s, const fs::path& dir,
                        std::vector<std::string>& overrides)
{
  overrides = bond_overrides;
  overrides.push_back(set("Damage/tensile strength", s * base.tensile));
  if (base.shear > 0)
    overrides.push_back(set("Damage/shear strength", s * base.shear));
  if (base.cohesion > 0)
    overrides.push_back(set("Damage/cohesion", s * base.cohesion));
  StrengthSample r = run_to_failure(file, overrides, dir);
  r.factor = s;
  r.tensile_strength = s * base.tensile;
  r.shear_strength = s * base.shear;
  r.cohesion = s * base.cohesion;
  return r;
}

/// The next factor: a secant through the last two runs, kept inside the bracket [lo, hi] the
/// runs established (bisection where it leaves it); the proportional step where there is no
/// second run.
double next_factor(const std::vector<StrengthSample>& runs, double target)
{
  const StrengthSample& s = runs.back();
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  for (const auto& r : runs)
    if (r.peak_stress < target)
      lo = std::max(lo, r.factor);
    else
      hi = std::min(hi, r.factor);
  double next = s.factor * target / s.peak_stress; // exact for a quasi-static brittle failure
  if (runs.size() >= 2)
  {
    const StrengthSample& p = runs[runs.size() - 2];
    const double slope = (s.peak_stress - p.peak_stress) / (s.factor - p.factor);
    if (slope > 0 && std::isfinite(slope))
      next = s.factor + (target - s.peak_stress) / slope;
  }
  if (!(next > lo && next < hi))
    next = std::isfinite(hi) ? 0.5 * (lo + hi) : 2 * lo;
  return next;
}
} // namespace

StrengthCalibration calibrate_strength(const fs::path& file,
                                       const std::vector<std::string>& bond_overrides,
                                       const std::string& bond_model, const CalibrationTargets& t,
                                       const fs::path& scratch, bool progress)
{
  StrengthCalibration c;
  c.case_file = file.string();
  const std::string name = file.filename().string();
  if (!fs::is_regular_file(file))
    throw std::runtime_error("Calibration/strength case: " + file.string() + ": no such file");
  BaseStrengths base;
  {
    auto prm = read_case(file.string(), bond_overrides);
    base = read_base(*prm, name, bond_model);
  }
  double s = 1;
  while (true)
  {
    if (int(c.iterations.size()) >= t.max_tension_runs)
    {
      c.failure =
          "Calibration/max strength runs: " + std::to_string(t.max_tension_runs) +
          " tension runs did not bring the peak stress within Calibration/strength tolerance";
      break;
    }
    const fs::path dir = scratch / ("tension_" + std::to_string(c.iterations.size() + 1));
    c.iterations.push_back(run_once(file, bond_overrides, base, s, dir, c.overrides));
    fs::remove_all(dir);
    const StrengthSample& r = c.iterations.back();
    if (progress)
      std::printf("calibrate: tension run %zu: strength factor %.6g (tensile strength %.6g Pa): "
                  "peak stress %.6g Pa\n",
                  c.iterations.size(), r.factor, r.tensile_strength, r.peak_stress);
    std::fflush(stdout);
    if (std::abs(r.peak_stress - t.tensile_strength) <= t.strength_tolerance * t.tensile_strength)
    {
      c.reached = true;
      break;
    }
    s = next_factor(c.iterations, t.tensile_strength);
  }
  return c;
}
} // namespace dembridge::app

namespace dembridge::app
{
void check_failure_cases(const fs::path& strength_case, const fs::path& compression_case,
                         const std::string& bond_model)
{
  if (!strength_case.empty())
    read_base(*read_case(strength_case.string(), {}), strength_case.filename().string(),
              bond_model);
  if (!compression_case.empty())
    check_compression_case(*read_case(compression_case.string(), {}),
                           compression_case.filename().string(), bond_model);
}

CompressionResult measure_compression(const fs::path& file,
                                      const std::vector<std::string>& calibrated_overrides,
                                      double tensile_strength, const CalibrationTargets& t,
                                      const std::string& bond_model, const fs::path& scratch)
{
  CompressionResult c;
  c.case_file = file.string();
  check_compression_case(*read_case(file.string(), calibrated_overrides), file.filename().string(),
                         bond_model);
  const StrengthSample r = run_to_failure(file, calibrated_overrides, scratch / "compression");
  fs::remove_all(scratch / "compression");
  c.peak_stress = r.peak_stress;
  c.seconds = r.seconds;
  c.ratio = r.peak_stress / tensile_strength;
  const double target = t.compressive_to_tensile_ratio;
  c.reached = !(target > 0) || std::abs(c.ratio - target) <= t.strength_tolerance * target;
  if (!c.reached)
  {
    std::ostringstream line;
    line << "Calibration/target compressive to tensile ratio: " << target << " is "
         << (target > c.ratio ? "beyond" : "below") << " what " << bond_model
         << " bonds give on this case: sigma_c / sigma_t = " << c.ratio
         << " at the calibrated strengths, and scaling them together keeps it (the case's "
            "ratio of shear to tensile bond strength sets it; Potyondy and Cundall (2004) "
            "report bonded-particle ratios far below rock's)";
    c.failure = line.str();
  }
  return c;
}
} // namespace dembridge::app
