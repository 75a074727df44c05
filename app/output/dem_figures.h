#pragma once
// summary.json figures of a DEM run (Mode = dem) from its measurements: the particle stresses
// (thesis eq. 62, Fig. 36, eq. 54), the static solver's geometry, the uniaxial test's moduli
// and Poisson's ratios (eqs. 64-65), the three-point bending test's flexural moduli (eqs. 67,
// 69) and the groups' displacements and forces. The physics is in dem/measurements/; these
// functions only choose what a run reports, under which key, and warn where a figure is
// undefined (result_warnings.h).
#include "dem/measurements/particle_stress.h"
#include "dem/model/model.h"
#include "dem/solvers/run_explicit.h"
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>
#include <vector>

namespace dembridge::app
{
/// The load histories an explicit run recorded, one entry per history record (empty for a
/// static run): what the moduli of a specimen that broke are fitted to.
struct LoadHistory
{
  std::vector<double> axial_displacement;  ///< loaded minus fixed end, along the modulus axis
  std::vector<double> axial_loaded_force;  ///< the loaded end's reaction
  std::vector<double> axial_fixed_force;   ///< minus the fixed end's reaction
  std::vector<double> flexural_load;       ///< the supports' vertical reactions
  std::vector<double> flexural_deflection; ///< mean of the loaded and bottom groups' downward u
  std::size_t flexural_records_intact = 0; ///< records before the first bond broke
};

nlohmann::json to_json(const dem::Vec3& v);
nlohmann::json to_json(const dem::Tensor3& t);

/// particle_stress.csv: reference position, radius and stress tensor (Pa) of every particle;
/// written under a temporary name and renamed, so a partial file never looks complete.
void write_particle_stresses(const std::filesystem::path& file, const dem::ParticleStore& p,
                             const dem::ParticleStresses& s);

/// particle_stress_histogram, stress_layers (Measurements/stress layers > 0; returned for the
/// uniaxial figures), strain_energy and, without a uniaxial test, the RVE stress over the
/// specimen's reference @p extent.
std::optional<dem::StressLayers>
add_particle_stress_figures(nlohmann::json& j, const dem::Model& model, const dem::MeasureConfig& m,
                            const dem::ParticleStresses& stresses,
                            const std::pair<dem::Vec3, dem::Vec3>& extent);

/// The static solver's geometry and max_rotation, with a warning when the rotations are too
/// large for its linear solution.
void add_static_geometry(nlohmann::json& j, const dem::Model& model);

/// The uniaxial test (Measurements/modulus groups): Young's modulus (the fit to the elastic part
/// of @p history when the specimen @p broke), Poisson's ratios, axial stress and strain, the
/// peak stress and the RVE stress between the end groups against the boundary stress.
void add_axial_figures(nlohmann::json& j, const dem::Model& model, const dem::MeasureConfig& m,
                       const dem::ParticleStresses& stresses,
                       const std::pair<dem::Vec3, dem::Vec3>& extent,
                       const std::optional<dem::StressLayers>& layers, const LoadHistory& history,
                       bool broke);

/// The three-point bending test (Measurements/flexural groups): flexural moduli (the fit to the
/// elastic part of @p history when the specimen @p broke) and the peak load.
void add_flexural_figures(nlohmann::json& j, const dem::Model& model, const dem::MeasureConfig& m,
                          const LoadHistory& history, bool broke);

/// groups: each group's size, mean displacement and total force.
void add_group_figures(nlohmann::json& j, const dem::Model& model);

/// An explicit run's energies (`energy`: each term, J), `energy_balance_error` and
/// `unbalanced_force_ratio`.
void add_energy_figures(nlohmann::json& j, const dem::RunResult& r);
} // namespace dembridge::app
