#pragma once
// The summary.json figures of a coupled run (app/runs/coupled_run.h): the run and its energies,
// the handshake band, the adaptive region's growth, the continuum's probes and reaction, and the
// particle region's groups, strain, cracks and peak load.
#include "coupling/coupled_case.h"
#include "coupling/coupled_problem.h"
#include "coupling/coupled_run.h"
#include "dem/measurements/failure_measurements.h"
#include "fem/elastic_problem.h"
#include <nlohmann/json.hpp>
#include <vector>

namespace dembridge::app
{
/// The run (steps, time, stop reason, time steps, wall times) and its energy balance.
void add_coupled_run_figures(nlohmann::json& j, coupling::CoupledProblem& p,
                             const coupling::CoupledRunResult& r);

/// The handshake band (its damage, width, weight floor, the continuum tensor), the adaptive
/// region's growth and, for a wave test, the reflected and transmitted energy.
void add_band_figures(nlohmann::json& j, coupling::CoupledProblem& p,
                      const coupling::CoupledCase& c, const coupling::CoupledRunResult& r);

/// The FE probes' displacements and their mean along the deflection direction (collective).
void add_fe_probe_figures(nlohmann::json& j, coupling::CoupledProblem& p,
                          const coupling::CoupledCase& c,
                          const std::vector<fem::PointProbe>& probes);

/// The FE reaction and, with a loaded boundary, E by thesis eq. 64 (as a FEM run:
/// fem_case.cc); warnings from rank 0 alone (@p root).
void add_fe_reaction_figures(nlohmann::json& j, coupling::CoupledProblem& p,
                             const coupling::CoupledCase& c, bool root);

/// What the particle region measured, on rank 0: its groups, the deflection, the particle-only
/// region's strain, the bonds, the cracks (@p failure_law), the peak load of @p loads against
/// @p load_displacements, the fracture energy.
nlohmann::json particle_region_figures(coupling::CoupledProblem& p, const coupling::CoupledCase& c,
                                       bool failure_law, const std::vector<dem::CrackEvent>& cracks,
                                       const std::vector<double>& loads,
                                       const std::vector<double>& load_displacements);
} // namespace dembridge::app
