// dembridge calibrate: the elastic and strength halves in turn, and the output folder
// (calibrate.h).
#include "app/studies/calibrate.h"
#include "app/input/calibration_parameters.h"
#include "app/input/case_file.h"
#include "app/input/dem_parameters.h"
#include "app/studies/calibrate_elastic.h"
#include "app/studies/calibrate_report.h"
#include "app/studies/calibrate_strength.h"
#include "app/studies/verify.h"
#include "app/studies/verify_report.h"
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

namespace dembridge::app
{
namespace fs = std::filesystem;
using nlohmann::json;
using namespace calibrate_detail;

namespace
{
/// Everything read from the targets file, checked before anything is written.
struct Inputs
{
  std::string name;
  fs::path case_dir;
  dem::CaseConfig config;
  CalibrationTargets targets;
  std::string bond_model;
  fs::path strength_case;    ///< absolute; empty without a strength target
  fs::path compression_case; ///< absolute; empty without one
  std::unique_ptr<ElasticProbe> probe;
};

/// @p file as written in Calibration/@p key, relative to the targets file; checked to exist.
fs::path case_relative(const fs::path& case_dir, const std::string& file, const std::string& key)
{
  if (file.empty())
    return {};
  const fs::path path = (case_dir / file).lexically_normal();
  if (!fs::is_regular_file(path))
    throw std::runtime_error("Calibration/" + key + ": " + file + ": no such file");
  return path;
}

Inputs read_inputs(const CalibrateOptions& o)
{
  Inputs in;
  in.name = fs::path(o.targets_file).filename().string();
  if (fs::path(o.targets_file).extension() != ".prm")
    throw std::runtime_error(in.name + ": calibrate reads .prm cases (the calibrated case is "
                                       "the file with its calibrated values appended)");
  auto prm = read_case(o.targets_file, o.overrides);
  if (prm->get("Mode") != "dem")
    throw std::runtime_error(in.name + ": Mode: calibrate needs a DEM case (Mode = dem)");
  in.case_dir = fs::absolute(o.targets_file).parent_path();
  try
  {
    in.targets = read_calibration_targets(*prm);
    in.bond_model = prm->get({"Bonds"}, "model");
    in.strength_case = case_relative(in.case_dir, in.targets.strength_case, "strength case");
    in.compression_case =
        case_relative(in.case_dir, in.targets.compression_case, "compression case");
    check_failure_cases(in.strength_case, in.compression_case, in.bond_model);
    WorkingDirectory cd(in.case_dir); // case-relative paths
    in.config = parse_dem_case(*prm);
    in.probe = std::make_unique<ElasticProbe>(in.config); // builds the packing
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(in.name + ": " + one_line(e.what()));
  }
  return in;
}

/// "Bonds/<key>=<value>" of the calibrated elastic parameters.
std::vector<std::string> bond_overrides(const ElasticCalibration& c)
{
  return {"Bonds/" + c.ratio_key + "=" + verify_detail::num(c.ratio_parameter),
          "Bonds/" + c.modulus_key + "=" + verify_detail::num(c.modulus_parameter)};
}

json targets_json(const CalibrationTargets& t)
{
  json j = {{"youngs_modulus", t.youngs_modulus},
            {"poisson_ratio", t.poisson_ratio},
            {"elastic_tolerance", t.elastic_tolerance},
            {"max_static_solves", t.max_static_solves}};
  if (t.tensile_strength > 0)
  {
    j["tensile_strength"] = t.tensile_strength;
    j["strength_tolerance"] = t.strength_tolerance;
    j["max_tension_runs"] = t.max_tension_runs;
  }
  if (t.compressive_to_tensile_ratio > 0)
    j["compressive_to_tensile_ratio"] = t.compressive_to_tensile_ratio;
  return j;
}

fs::path output_folder(const CalibrateOptions& o)
{
  return o.output_dir.empty()
             ? fs::path("output") / ("calibrate_" + fs::path(o.targets_file).stem().string())
             : fs::path(o.output_dir);
}
} // namespace

namespace
{
/// The calibrated elastic parameters on the packings of Calibration/spread seeds and spread box
/// size: one model and one static solve each, reported beside the calibrated packing's values.
json spread_json(const CalibrateOptions& o, const Inputs& in, const ElasticCalibration& e)
{
  std::vector<std::pair<std::string, std::string>> checks; // label, override
  for (const long seed : in.targets.spread_seeds)
    checks.emplace_back("seed " + std::to_string(seed), "Particles/seed=" + std::to_string(seed));
  if (!in.targets.spread_box_size.empty())
    checks.emplace_back("box size " + in.targets.spread_box_size,
                        "Particles/box size=" + in.targets.spread_box_size);
  const ElasticSample& calibrated = e.iterations.back();
  json rows = json::array();
  double e_spread = 0, nu_spread = 0;
  for (const auto& [label, extra] : checks)
  {
    std::vector<std::string> overrides = o.overrides;
    overrides.push_back(extra);
    auto prm = read_case(o.targets_file, overrides);
    dem::CaseConfig config;
    {
      WorkingDirectory cd(in.case_dir);
      config = parse_dem_case(*prm);
    }
    ElasticProbe probe(config);
    const ElasticSample s = probe.measure(e.ratio_parameter, e.modulus_parameter);
    const double de = s.youngs_modulus / calibrated.youngs_modulus - 1;
    const double dnu = s.poisson_ratio - calibrated.poisson_ratio;
    e_spread = std::max(e_spread, std::abs(de)), nu_spread = std::max(nu_spread, std::abs(dnu));
    rows.push_back({{"packing", label},
                    {"n_particles", probe.model().particles.size()},
                    {"youngs_modulus", s.youngs_modulus},
                    {"poisson_ratio", s.poisson_ratio},
                    {"youngs_modulus_relative_deviation", de},
                    {"poisson_ratio_deviation", dnu}});
    if (o.progress)
      std::printf("calibrate: check on %s (%zu particles): E = %.6g Pa (%+.2f %%), nu = %.6g "
                  "(%+.4f)\n",
                  label.c_str(), probe.model().particles.size(), s.youngs_modulus, 100 * de,
                  s.poisson_ratio, dnu);
    std::fflush(stdout);
  }
  return {{"method", "the calibrated Bonds values on further packings, one static solve each; "
                     "reported, not iterated on"},
          {"checks", rows},
          {"largest_youngs_modulus_relative_deviation", e_spread},
          {"largest_poisson_ratio_deviation", nu_spread}};
}

/// The strength half, when a tensile strength is a target and the elastic half was reached;
/// records it in j and adds its calibrated strengths to j["calibrated"]. With a compression
/// case, sigma_c / sigma_t at the calibrated strengths too (j["compression"]).
std::optional<StrengthCalibration> calibrate_strengths(const Inputs& in,
                                                       const ElasticCalibration& elastic,
                                                       const CalibrateOptions& o,
                                                       const fs::path& dir, json& j)
{
  if (!(in.targets.tensile_strength > 0))
    return std::nullopt;
  if (!elastic.reached)
  {
    j["strength"] = {{"reached", false},
                     {"tension_runs", 0},
                     {"failure", "not run: the elastic calibration was not reached"}};
    return std::nullopt;
  }
  const fs::path scratch = dir / "strength_runs";
  // the runs' folders go with the command, also when a run fails
  struct RemoveScratch
  {
    fs::path path;
    ~RemoveScratch() { fs::remove_all(path); }
  } remove_scratch{scratch};
  StrengthCalibration s = calibrate_strength(in.strength_case, bond_overrides(elastic),
                                             in.bond_model, in.targets, scratch, o.progress);
  j["strength"] = strength_json(s, in.targets);
  if (s.reached)
    for (const std::string& set : s.overrides)
      if (set.rfind("Damage/", 0) == 0)
        j["calibrated"][set.substr(0, set.find('='))] = std::stod(set.substr(set.find('=') + 1));
  if (s.reached && !in.compression_case.empty())
  {
    const CompressionResult c =
        measure_compression(in.compression_case, s.overrides, s.iterations.back().peak_stress,
                            in.targets, in.bond_model, scratch);
    j["compression"] = {{"compression_case", in.targets.compression_case},
                        {"peak_stress", c.peak_stress},
                        {"compressive_to_tensile_ratio", c.ratio},
                        {"run_seconds", c.seconds},
                        {"reached", c.reached}};
    if (in.targets.compressive_to_tensile_ratio > 0)
      j["compression"]["target"] = in.targets.compressive_to_tensile_ratio;
    if (!c.reached)
      j["compression"]["failure"] = c.failure;
    if (o.progress)
      std::printf("calibrate: compression run: peak stress %.6g Pa, sigma_c / sigma_t = %.4g\n",
                  c.peak_stress, c.ratio);
  }
  return s;
}

/// calibrated.prm and calibrated_strength.prm; the names written.
json write_cases(const CalibrateOptions& o, const Inputs& in, const ElasticCalibration& e,
                 const std::optional<StrengthCalibration>& s, const fs::path& dir)
{
  json files = json::array();
  write_text_atomically(dir, "calibrated.prm",
                        overridden_case_text(o.targets_file, o.overrides, bond_overrides(e),
                                             "dembridge calibrate: " + in.name +
                                                 " with the calibrated bond parameters "
                                                 "(calibration.json)"));
  files.push_back("calibrated.prm");
  if (s)
  {
    write_text_atomically(
        dir, "calibrated_strength.prm",
        overridden_case_text(in.strength_case, {}, s->overrides,
                             "dembridge calibrate: " + in.strength_case.filename().string() +
                                 " with the calibrated bond and strength "
                                 "parameters (calibration.json)"));
    files.push_back("calibrated_strength.prm");
  }
  return files;
}
} // namespace

CalibrationResult calibrate(const CalibrateOptions& o)
{
  const auto start = std::chrono::steady_clock::now();
  Inputs in = read_inputs(o); // every input checked before anything is written
  CalibrationResult r;
  r.output_dir = output_folder(o);
  fs::create_directories(r.output_dir);
  // an earlier calibration's files must not pass for this one's
  for (const char* f :
       {"calibration.json", "calibration.png", "calibrated.prm", "calibrated_strength.prm"})
    fs::remove(r.output_dir / f);
  json& j = r.report;
  j["targets_file"] = in.name;
  j["bond_model"] = in.bond_model;
  j["targets"] = targets_json(in.targets);
  j["n_particles"] = in.probe->model().particles.size();
  j["n_bonds"] = in.probe->model().bonds.size();
  const ElasticCalibration e =
      calibrate_elastic(*in.probe, in.config.bonds.material, in.targets, o.progress);
  j["elastic"] = elastic_json(e, in.targets);
  // the values of the last solve are calibrated only when it reached the targets
  j[e.reached ? "calibrated" : "last_solve_parameters"] = {
      {"Bonds/" + e.ratio_key, e.ratio_parameter}, {"Bonds/" + e.modulus_key, e.modulus_parameter}};
  if (e.reached && (!in.targets.spread_seeds.empty() || !in.targets.spread_box_size.empty()))
    j["spread"] = spread_json(o, in, e);
  const auto s = calibrate_strengths(in, e, o, r.output_dir, j);
  r.failure = !e.reached ? e.failure : (s && !s->reached ? s->failure : "");
  // E, nu and sigma_t reached: the calibrated cases are written even when the ratio sigma_c /
  // sigma_t is out of reach (a measured property of the bond model, reported as such)
  const bool written = r.failure.empty();
  if (written && j.contains("compression") && !j["compression"]["reached"].get<bool>())
    r.failure = j["compression"]["failure"].get<std::string>();
  r.reached = r.failure.empty();
  j["reached"] = r.reached;
  if (!r.reached)
    j["failure"] = r.failure;
  j["files"] = written ? write_cases(o, in, e, s, r.output_dir) : json::array();
  j["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  verify_detail::write_json_atomically(r.output_dir, "calibration.json", j);
  if (o.plot)
  {
    j["plot"] = write_plot(r.output_dir);
    verify_detail::write_json_atomically(r.output_dir, "calibration.json", j);
  }
  return r;
}

int run_calibrate(const CalibrateOptions& o)
{
  const CalibrationResult r = calibrate(o);
  const json& j = r.report;
  std::printf(
      "calibrate: %s, %zu particles, %zu bonds (%s): %ld static solves%s\n",
      j["targets_file"].get<std::string>().c_str(), j["n_particles"].get<std::size_t>(),
      j["n_bonds"].get<std::size_t>(), j["bond_model"].get<std::string>().c_str(),
      j["elastic"]["static_solves"].get<long>(),
      j.contains("strength")
          ? (", " + std::to_string(j["strength"]["tension_runs"].get<long>()) + " tension runs")
                .c_str()
          : "");
  if (j.contains("calibrated"))
    for (const auto& [key, value] : j["calibrated"].items())
      std::printf("  %-32s %.10g\n", key.c_str(), value.get<double>());
  std::cout << "dembridge: wrote " << (r.output_dir / "calibration.json").string() << std::endl;
  if (!r.reached)
    throw std::runtime_error(j["targets_file"].get<std::string>() + ": " + r.failure);
  return 0;
}
} // namespace dembridge::app
