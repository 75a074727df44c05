#include "app/output/coupled_figures.h"
#include "app/output/crack_output.h"
#include "app/output/result_warnings.h"
#include "coupling/fixed_region.h"
#include "coupling/measurements.h"
#include "dem/measurements/measurements.h"
#include "fem/reaction_measurement.h"
#include <algorithm>

namespace dembridge::app
{
namespace
{
using coupling::CoupledProblem;

nlohmann::json to_json(const dem::Vec3& v)
{
  return {v.x(), v.y(), v.z()};
}

/// The adaptive region's growth (summary.json): the events, the largest energy jump relative to
/// the body's strain energy, the cap.
void add_growth_summary(nlohmann::json& j, const CoupledProblem& p)
{
  const auto& a = *p.adaptive_region();
  nlohmann::json events = nlohmann::json::array();
  double largest = 0;
  for (const auto& e : p.growth_events())
  {
    events.push_back({{"time", e.time},
                      {"step", e.step},
                      {"marked_cells", e.marked_cells},
                      {"marked_by_band_bonds", e.marked_by_bonds},
                      {"max_utilisation", e.max_utilisation},
                      {"cells_added", e.cells_added},
                      {"region_cells", e.region_cells},
                      {"particles_added", e.particles_added},
                      {"n_particles", e.n_particles},
                      {"bonds_added", e.bonds_added},
                      {"energy_jump", e.energy_jump()},
                      {"energy_jump_ratio", e.energy_jump_ratio()},
                      {"strain_energy", e.strain_energy},
                      {"time_step", e.time_step}});
    largest = std::max(largest, e.energy_jump_ratio());
  }
  j["region_growth_events"] = events;
  j["n_region_growth_events"] = events.size();
  j["n_particles_final"] = p.n_particles();
  j["growth_energy_jump_max"] = largest;
  j["region_cells_final"] = a.n_region_cells();
  j["region_final_cells"] = coupling::region_cells(a).to_json(); // compare's fixed-region model
  j["particle_region_packing_fraction"] =
      double(a.n_region_particles()) / double(std::max<std::size_t>(1, a.packing().size()));
  j["max_utilisation"] = a.largest_utilisation();
  j["region_growth_capped"] = p.growth_cap().reached;
  if (p.growth_cap().reached)
    j["region_growth_capped_time"] = p.growth_cap().time;
}

nlohmann::json energies_json(const CoupledProblem::Energies& e)
{
  return {{"dem_kinetic", e.dem_kinetic},
          {"dem_strain", e.dem_strain},
          {"dem_damping", e.dem_damping},
          {"dem_external_work", e.dem_external},
          {"dem_contacts_and_fracture", e.dem_other},
          {"dem_total", e.dem_total()},
          {"fe_kinetic", e.fe_kinetic},
          {"fe_strain", e.fe_strain},
          {"fe_damping", e.fe_damping},
          {"fe_boundary_work", e.fe_boundary_work},
          {"fe_total", e.fe_total()},
          {"multiplier_work_particles", e.multiplier_work_particles},
          {"multiplier_work_fe", e.multiplier_work_fe},
          {"multiplier_work", e.multiplier_work()},
          {"initial", e.initial}};
}
} // namespace

void add_coupled_run_figures(nlohmann::json& j, CoupledProblem& p,
                             const coupling::CoupledRunResult& r)
{
  j["mode"] = "coupled";
  // the particles' bonds are co-rotational, the continuum is linear elastic (small strains)
  j["geometry"] = "particles nonlinear (large displacements and rotations), continuum linear "
                  "(small displacements)";
  j["n_particles"] = p.n_particles();
  j["n_interface_particles"] = p.n_interface_particles();
  // the continuum now: an adaptive region's growth replaces it
  j["n_fe_dofs"] = p.continuum().n_dofs();
  j["n_fe_cells"] = p.continuum().n_cells();
  j["time_step"] = p.time_step();
  j["particle_time_step"] = p.particle_time_step();
  j["fe_time_step"] = p.fe_time_step();
  // the coupled run's stable step over the particle region's own (the goal: at least 0.9)
  j["stable_time_step_ratio"] =
      std::min(p.particle_time_step(), p.fe_time_step()) / p.particle_time_step();
  j["steps"] = r.steps;
  j["simulated_time"] = r.time;
  j["stop_reason"] = r.stop_reason;
  j["solver_seconds"] = r.wall_seconds;
  j["coupling_seconds"] = r.coupling_seconds;
  j["coupling_share"] = r.wall_seconds > 0 ? r.coupling_seconds / r.wall_seconds : 0.0;
  j["energy"] = energies_json(r.energies);
  j["energy_balance_error"] = r.energies.balance_error();
  j["energy_balance_error_max"] = r.max_balance_error;
  j["max_tie_gap"] = r.max_tie_gap;
}

void add_band_figures(nlohmann::json& j, CoupledProblem& p, const coupling::CoupledCase& c,
                      const coupling::CoupledRunResult& r)
{
  {
    const auto& bd = p.band_damage();
    j["n_band_bonds"] = bd.n_band_bonds;
    j["damage_reached_band"] = bd.reached;
    j["band_failure_index_max"] = bd.max_failure_index;
    if (bd.reached)
      j["damage_reached_band_time"] = bd.first_time;
  }
  if (p.adaptive_region())
    add_growth_summary(j, p);
  j["band_width"] = c.settings.geometry.band_width;
  j["weight_floor"] = c.settings.geometry.weight_floor;
  {
    nlohmann::json C = nlohmann::json::array();
    for (int i = 0; i < 6; ++i)
    {
      nlohmann::json row = nlohmann::json::array();
      for (int k = 0; k < 6; ++k)
        row.push_back(c.settings.tensor[6 * i + k]);
      C.push_back(row);
    }
    j["continuum_tensor"] = C;
  }
  if (r.reflected_energy_ratio >= 0)
  {
    j["reflected_energy_ratio"] = r.reflected_energy_ratio;
    j["transmitted_energy_ratio"] = r.transmitted_energy_ratio;
  }
}

void add_fe_probe_figures(nlohmann::json& j, CoupledProblem& p, const coupling::CoupledCase& c,
                          const std::vector<fem::PointProbe>& probes)
{
  if (probes.empty())
    return;
  nlohmann::json u = nlohmann::json::array();
  double mean = 0;
  dealii::Tensor<1, 3> direction;
  for (int d = 0; d < 3; ++d)
    direction[d] = c.continuum.deflection_direction[d];
  for (const auto& probe : probes)
  {
    const auto v = p.continuum().probe_vector(probe);
    u.push_back({v[0], v[1], v[2]});
    mean += v * direction / double(probes.size());
  }
  j["fe_probe_displacements"] = u;
  j["fe_" + c.continuum.deflection_name] = mean;
}

void add_fe_reaction_figures(nlohmann::json& j, CoupledProblem& p, const coupling::CoupledCase& c,
                             bool root)
{
  const auto& fp = c.continuum;
  const auto m = fem::measure_reaction(p.continuum(), fp);
  if (!m)
    return;
  j["reaction_force"] = m->reaction_along;
  j["reaction_force_vector"] = {m->reaction[0], m->reaction[1], m->reaction[2]};
  if (!m->has_loaded_boundary)
    return;
  j["area"] = m->area;
  j["gauge_length"] = m->gauge_length;
  j["elongation"] = m->elongation;
  j["axial_strain"] = m->elongation / m->gauge_length;
  if (m->elongation == 0)
  {
    j["youngs_modulus"] = nullptr;
    add_warning(j,
                "youngs_modulus: undefined: the loaded boundary '" + fp.loaded_boundary +
                    "' did not move relative to the reaction boundary '" + fp.reaction_boundary +
                    "' (elongation 0); written as null",
                root);
    return;
  }
  j["youngs_modulus"] = m->youngs_modulus;
  if (m->reaction_along == 0)
    add_warning(j,
                "youngs_modulus: 0: the reaction boundary '" + fp.reaction_boundary +
                    "' carries no load along the reaction direction (reaction_force 0)",
                root);
}

nlohmann::json particle_region_figures(CoupledProblem& p, const coupling::CoupledCase& c,
                                       bool failure_law, const std::vector<dem::CrackEvent>& cracks,
                                       const std::vector<double>& loads,
                                       const std::vector<double>& load_displacements)
{
  nlohmann::json groups;
  const auto& model = p.model();
  for (const auto& g : model.groups)
  {
    groups[g.name]["n_particles"] = g.members.size();
    groups[g.name]["mean_displacement"] = to_json(dem::mean_displacement(model.particles, g));
  }
  nlohmann::json measured;
  const auto& m = c.particles.measure;
  if (!m.deflection_group.empty())
  {
    const auto& g =
        model.groups[model.group_index(m.deflection_group, "Measurements/deflection group")];
    const dem::Vec3 u = dem::mean_displacement(model.particles, g);
    measured[m.deflection_name] = u.dot(m.deflection_direction.normalized());
    measured[m.deflection_name + "_vector"] = to_json(u);
  }
  measured["groups"] = groups;
  // the particle-only region's own strain: least-squares affine fit of its displacements
  const auto& h = p.handshake();
  const auto eps = coupling::fit_particle_strain(model.particles, [&](const dem::Vec3& X)
                                                 { return h.in_particle_only(X); });
  measured["particle_strain"] = {
      {eps[0], eps[1], eps[2]}, {eps[3], eps[4], eps[5]}, {eps[6], eps[7], eps[8]}};
  measured["n_bonds"] = model.bonds.size();
  // cracks (the particle region's): counts by mode, the first, broken fraction per slab
  if (failure_law)
    add_crack_summary(measured, cracks, model.particles, model.bonds, m.stress_layers,
                      m.stress_layer_axis);
  if (!loads.empty()) // peak_load (N), deflection_at_peak (m)
    add_peak_load(measured, loads, load_displacements);
  measured["fracture_energy"] = p.fracture_energy();
  return measured;
}
} // namespace dembridge::app
