#include "app/output/dem_figures.h"
#include "app/output/crack_output.h"
#include "app/output/result_warnings.h"
#include "dem/core/output_file.h"
#include "dem/measurements/failure_measurements.h"
#include "dem/measurements/measurements.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <string>

namespace dembridge::app
{
namespace
{
/// Rotations (rad) above which a linear (static) solution is flagged: it differs from the
/// large-rotation one by about half the rotation squared (a cantilever's tip deflection against
/// the explicit solver's: 1.2e-5 at 5.1e-3 rad, 1.4e-4 at 0.017 rad, 1.2e-3 at 0.051 rad), 5e-5
/// here.
constexpr double max_linear_rotation = 1e-2;
} // namespace

nlohmann::json to_json(const dem::Vec3& v)
{
  return {v.x(), v.y(), v.z()};
}

nlohmann::json to_json(const dem::Tensor3& t)
{
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    rows.push_back({t(r, 0), t(r, 1), t(r, 2)});
  return rows;
}

void write_particle_stresses(const std::filesystem::path& file, const dem::ParticleStore& p,
                             const dem::ParticleStresses& s)
{
  const std::filesystem::path part = file.string() + ".part";
  {
    dem::OutputFile out(part); // failures name the file and the reason
    out << "id,x,y,z,radius,s_xx,s_yy,s_zz,s_yz,s_xz,s_xy\n" << std::setprecision(10);
    // rows in the user's particle numbering (the stores are in spatial order, renumbering.h)
    std::vector<std::size_t> by_id(p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      by_id[std::size_t(p.id[i])] = i;
    for (const std::size_t i : by_id)
    {
      const auto& x = p.reference_position[i];
      const auto& t = s.sigma[i];
      // symmetric part (the antisymmetric part is the neglected couples' share)
      out << p.id[i] << ',' << x.x() << ',' << x.y() << ',' << x.z() << ',' << p.radius[i] << ','
          << t(0, 0) << ',' << t(1, 1) << ',' << t(2, 2) << ',' << 0.5 * (t(1, 2) + t(2, 1)) << ','
          << 0.5 * (t(0, 2) + t(2, 0)) << ',' << 0.5 * (t(0, 1) + t(1, 0)) << '\n';
    }
    out.close();
  }
  std::filesystem::rename(part, file);
}

std::optional<dem::StressLayers>
add_particle_stress_figures(nlohmann::json& j, const dem::Model& model, const dem::MeasureConfig& m,
                            const dem::ParticleStresses& stresses,
                            const std::pair<dem::Vec3, dem::Vec3>& extent)
{
  {
    const int c = m.modulus_fixed_group.empty() ? 0 : m.modulus_axis;
    const auto h = dem::stress_histogram(stresses, c, m.stress_histogram_bins);
    j["particle_stress_histogram"] = {{"component", std::string(2, "xyz"[c])},
                                      {"mean", h.mean},
                                      {"std_dev", h.std_dev},
                                      {"max_ratio", h.max_ratio},
                                      {"edges", h.edges},
                                      {"counts", h.counts}};
  }
  std::optional<dem::StressLayers> layers;
  if (m.stress_layers > 0)
  {
    const auto& l =
        layers.emplace(dem::stress_layers(model.particles, stresses, extent.first, extent.second,
                                          m.stress_layer_axis, m.stress_layers));
    nlohmann::json sig = nlohmann::json::array();
    for (const auto& t : l.sigma)
      sig.push_back(to_json(t));
    j["stress_layers"] = {{"axis", std::string(1, "xyz"[l.axis])},
                          {"edges", l.edges},
                          {"n_particles", l.count},
                          {"sigma", sig}};
  }
  j["strain_energy"] = stresses.strain_energy;
  if (m.modulus_fixed_group.empty())
  {
    // no uniaxial test: the average over the specimen's extent (eq. 54 with V = extent volume)
    const double volume = (extent.second - extent.first).prod();
    j["rve_stress"] =
        to_json(dem::rve_average(model.particles, stresses, extent.first, extent.second, volume));
    j["rve_volume"] = volume;
  }
  return layers;
}

void add_static_geometry(nlohmann::json& j, const dem::Model& model)
{
  // the static solver is linear in the displacements and rotations (static_solver.h)
  j["geometry"] = "linear (small displacements and rotations)";
  const double max_rotation = dem::largest_rotation(model.particles, model.bonds);
  j["max_rotation"] = max_rotation;
  if (max_rotation > max_linear_rotation)
  {
    char line[400];
    std::snprintf(line, sizeof line,
                  "max_rotation: %.3g rad: the static solver is linear (small rotations), and "
                  "its figures differ from the large-rotation solution by about half the "
                  "rotation squared (%.2g) here; Simulation/solver = explicit follows large "
                  "rotations",
                  max_rotation, 0.5 * std::pow(max_rotation, 2));
    add_warning(j, line);
  }
}

namespace
{
/// E (or a broken specimen's final secant modulus), the axial stress, strain and force, the
/// Poisson's ratios from the end groups' response @p a; null with a warning where undefined.
void add_axial_response(nlohmann::json& j, const dem::AxialResponse& a, bool broke)
{
  const std::string axes = "xyz";
  // a specimen that broke: its final state is past the peak (a secant through the damage),
  // so E comes from the elastic part of the curve and the final ratios keep their own names
  const std::string nu = broke ? "final_poisson_ratio_" : "poisson_ratio_";
  j[broke ? "final_secant_modulus" : "youngs_modulus"] = a.youngs_modulus;
  j["axial_stress"] = a.stress;
  j["axial_strain"] = a.strain;
  j["axial_force"] = a.force;
  j["cross_section_area"] = a.area;
  j["gauge_length"] = a.gauge_length;
  for (int d = 0; d < 3; ++d)
    if (d != a.axis)
      j[nu + axes[a.axis] + axes[d]] = a.poisson_ratio[d];
  if (a.strain == 0)
  {
    const std::string key = broke ? "final_secant_modulus" : "youngs_modulus";
    j[key] = nullptr;
    for (int d = 0; d < 3; ++d)
      if (d != a.axis)
        j[nu + axes[a.axis] + axes[d]] = nullptr;
    add_warning(j, key +
                       ": undefined, and the Poisson's ratios with it: the end groups "
                       "(Measurements/modulus groups) did not move apart along " +
                       axes[a.axis] + " (axial strain 0); written as null");
  }
  else if (a.force == 0 && !broke)
    add_warning(j, "youngs_modulus: 0: the end groups (Measurements/modulus groups) carry no "
                   "axial load (reaction 0)");
}

/// E fitted to the load history (of its elastic part when bonds broke), and the peak stress.
void add_fitted_modulus(nlohmann::json& j, const dem::AxialResponse& a, const LoadHistory& history,
                        bool broke)
{
  const auto& du = history.axial_displacement;
  if (du.size() >= 3)
  {
    const auto& force = a.force_controlled ? history.axial_fixed_force : history.axial_loaded_force;
    // E from the elastic part of the curve (up to half the peak load) when bonds broke
    const std::size_t n_fit =
        broke ? std::max<std::size_t>(3, dem::records_before(force, 0.5)) : force.size();
    const auto fit = dem::fit_youngs_modulus({du.begin(), du.begin() + long(n_fit)},
                                             {force.begin(), force.begin() + long(n_fit)}, a);
    j["youngs_modulus_fit"] = fit.youngs_modulus;
    j["youngs_modulus_fit_points"] = fit.points;
    if (broke)
      j["youngs_modulus"] = fit.youngs_modulus;
    if (fit.points < 2 || fit.youngs_modulus == 0)
    {
      const std::string key = broke ? "youngs_modulus" : "youngs_modulus_fit";
      j[key] = nullptr;
      add_warning(j, key + ": undefined: the load history has no rising part to fit (" +
                         std::to_string(fit.points) + " records); written as null");
    }
    // the load transmitted through the specimen, read at the fixed end as a testing machine's
    // load cell does: the driven end's reaction also carries the local damping's drag on the
    // moving particles (5 % at the peak of tension_failure.prm), and its noise
    add_peak_stress(j, history.axial_fixed_force, du, a.area, a.gauge_length);
  }
  else if (broke)
  {
    j["youngs_modulus"] = nullptr;
    add_warning(j, "youngs_modulus: undefined: bonds broke and the load history has " +
                       std::to_string(du.size()) +
                       " records, too few to fit the elastic part (Output/history interval)");
  }
}

/// The RVE average stress of the specimen between the loaded planes against the boundary
/// stress, and the slab averages of the stress layers.
void add_rve_figures(nlohmann::json& j, const dem::Model& model, const dem::AxialResponse& a,
                     const dem::ParticleStresses& stresses,
                     const std::pair<dem::Vec3, dem::Vec3>& extent,
                     const std::optional<dem::StressLayers>& layers)
{
  // RVE = the specimen between the planes where the end loads act (gauge length x area).
  j["boundary_stress"] = a.stress;
  const dem::Tensor3 rve = dem::rve_average(model.particles, stresses, extent.first, extent.second,
                                            a.area * a.gauge_length);
  j["rve_stress"] = to_json(rve);
  j["rve_volume"] = a.area * a.gauge_length;
  j["rve_stress_asymmetry"] = (rve - rve.transpose()).norm() / std::max(rve.norm(), 1e-300);
  j["rve_stress_difference"] =
      a.stress != 0 ? std::abs(rve(a.axis, a.axis) - a.stress) / std::abs(a.stress) : 0.0;
  if (layers && a.stress != 0)
  {
    // slab averages of the loading-direction normal stress over the boundary stress (Fig. 37)
    std::vector<double> ratio;
    for (const auto& t : layers->sigma)
      ratio.push_back(t(a.axis, a.axis) / a.stress);
    j["stress_layers"]["normal_stress_ratio"] = ratio;
  }
}
} // namespace

void add_axial_figures(nlohmann::json& j, const dem::Model& model, const dem::MeasureConfig& m,
                       const dem::ParticleStresses& stresses,
                       const std::pair<dem::Vec3, dem::Vec3>& extent,
                       const std::optional<dem::StressLayers>& layers, const LoadHistory& history,
                       bool broke)
{
  const auto a = dem::axial_response(
      model.particles,
      model.groups[model.group_index(m.modulus_fixed_group, "Measurements/modulus groups")],
      model.groups[model.group_index(m.modulus_loaded_group, "Measurements/modulus groups")],
      m.modulus_axis, m.section_area[m.modulus_axis]);
  add_axial_response(j, a, broke);
  add_fitted_modulus(j, a, history, broke);
  add_rve_figures(j, model, a, stresses, extent, layers);
}

void add_flexural_figures(nlohmann::json& j, const dem::Model& model, const dem::MeasureConfig& m,
                          const LoadHistory& history, bool broke)
{
  auto group = [&](int k) -> const dem::Group&
  { return model.groups[model.group_index(m.flexural_groups[k], "Measurements/flexural groups")]; };
  const auto f = dem::flexural_response(model.particles, group(0), group(1), group(2), group(3), 0,
                                        2, m.flexural_poisson_ratio, m.form_factor);
  const auto& load = history.flexural_load;
  const auto& deflection = history.flexural_deflection;
  j["flexural_load"] = f.load;
  j["span"] = f.span;
  j["load_length"] = f.load_length;
  j["midspan_deflection"] = f.deflection;
  j["bottom_deflection"] = f.bottom_deflection;
  if (broke)
  {
    // past the peak the final ratio is a secant through the damage: E_f (eq. 69) from the
    // elastic part of the load-deflection curve, the records before the first bond broke (or
    // up to half the peak load when a weak bond broke earlier)
    j["final_secant_modulus"] = f.flexural_modulus;
    const std::size_t n_fit =
        std::max(history.flexural_records_intact, dem::records_before(load, 0.5));
    const auto fit =
        dem::fit_flexural_modulus({deflection.begin(), deflection.begin() + long(n_fit)},
                                  {load.begin(), load.begin() + long(n_fit)}, f);
    j["flexural_modulus_fit_points"] = fit.points;
    j["flexural_modulus"] = fit.youngs_modulus;
    if (fit.points < 2 || fit.youngs_modulus == 0)
    {
      j["flexural_modulus"] = nullptr;
      add_warning(j, "flexural_modulus: undefined: bonds broke and the load history has no "
                     "rising part to fit (" +
                         std::to_string(fit.points) +
                         " records; Output/history interval); written as null");
    }
  }
  else if (!(f.deflection > 0))
  {
    j["flexural_modulus"] = nullptr;
    add_warning(j, "flexural_modulus: undefined: the midspan did not deflect (Measurements/"
                   "flexural groups: the loaded and bottom groups); written as null");
  }
  else
  {
    j["flexural_modulus_point_load"] = f.flexural_modulus_point;
    j["flexural_modulus"] = f.flexural_modulus;
    j["flexural_modulus_bottom"] = f.flexural_modulus_bottom;
    if (f.load == 0)
      add_warning(j, "flexural_modulus: 0: the supports (Measurements/flexural groups) carry "
                     "no load (reaction 0)");
  }
  add_peak_load(j, load, deflection);
}

void add_group_figures(nlohmann::json& j, const dem::Model& model)
{
  auto& groups = j["groups"];
  for (const auto& g : model.groups)
  {
    groups[g.name]["n_particles"] = g.members.size();
    groups[g.name]["mean_displacement"] = to_json(dem::mean_displacement(model.particles, g));
    groups[g.name]["force"] = to_json(dem::total_force(model.particles, g));
  }
}

void add_energy_figures(nlohmann::json& j, const dem::RunResult& r)
{
  j["energy"] = {{"kinetic", r.energy.kinetic},     {"strain", r.energy.strain},
                 {"damping", r.energy.damping},     {"external_work", r.energy.external},
                 {"fracture", r.energy.fracture},   {"contact_strain", r.energy.contact_strain},
                 {"friction", r.energy.friction},   {"contact_damping", r.energy.contact_damping},
                 {"wall_work", r.energy.wall_work}, {"initial", r.energy.initial}};
  j["energy_balance_error"] = r.energy_balance_error;
  j["unbalanced_force_ratio"] = r.unbalanced_force_ratio;
}
} // namespace dembridge::app
