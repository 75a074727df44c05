#pragma once
// dembridge compare, the figures half: the runs' history and crack files read back, the
// load-deflection curve of each model, its figures (peak and limit load, initial stiffness,
// fracture energy, first crack) and one model against another (ratios, speed-up, the first
// cracks' distance). Internal to app/studies/compare.cc.
#include "dem/core/types.h"
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dembridge::app::compare_detail
{
/// A CSV file with a header line: the columns by name, the rows as numbers (NaN where a cell is
/// not one).
struct Table
{
  std::map<std::string, std::size_t> column;
  std::vector<std::vector<double>> rows;
  /// The column @p name; throws std::runtime_error naming @p file when it has none.
  std::vector<double> get(const std::string& name, const std::string& file) const;
};

Table read_csv(const std::filesystem::path& file);

struct Curve
{
  std::vector<double> deflection, load;
};

/// The curves of the particle models in the order they are written (coupled, [coupled_fixed,]
/// full_dem), and the FE reference's stiffness (its curve is a line).
struct ModelCurves
{
  std::vector<std::pair<std::string, Curve>> curves;
  double fe_stiffness = 0;
};

/// The load-deflection curve of a coupled run (its own measure: load_displacement, load).
Curve coupled_curve(const Table& h, const std::string& file);

/// The full-DEM curve: the loaded group @p g's displacement and force along the push.
Curve dem_curve_of(const Table& h, const std::string& g, const dem::Vec3& direction,
                   const std::string& file);

/// The box the FE reference leaves out (Particles/remove box), and whether there is one.
struct Notch
{
  dem::Vec3 lower, upper;
  bool present = false;
};

/// One particle model's figures: those of its curve (peak and limit load, initial stiffness),
/// its run's wall time, memory, particles and broken bonds from @p summary, the fracture energy,
/// and its first crack (run_dir/cracks.csv) with its distance to the notch.
nlohmann::json model_figures(const nlohmann::json& summary, const Curve& curve,
                             const std::vector<double>& broken, double fracture_energy,
                             const std::filesystem::path& run_dir, const Notch& notch);

/// A coupled run's figures (model_figures, the fracture energy the particle region's: no other
/// part can break) and its FE dofs, coupling share and whether damage reached the band.
nlohmann::json coupled_model_figures(const nlohmann::json& summary, const Table& h,
                                     const Curve& curve, const std::string& name,
                                     const std::filesystem::path& dir, const Notch& notch);

/// Model a against model b: the ratios of their figures, the speed-up (b's wall time over a's)
/// and the distance between their first cracks.
nlohmann::json versus(const nlohmann::json& a, const nlohmann::json& b);

/// What an adaptive run's summary says of its region's growth.
void add_growth_figures(nlohmann::json& model, const nlohmann::json& summary);
} // namespace dembridge::app::compare_detail
