#pragma once
// A static DEM run (Simulation/solver = static) in load steps: Simulation/load steps solves the
// linear equilibrium for the loads at t_k = k T / N (T = Simulation/end time), the last step
// being the solver's final state (loads at full value, finite end times past; see
// dem/solvers/static_solver.h). Each step writes a history.csv row with the explicit run's
// columns (kinetic and damping energy zero; external work equal to the strain energy, as
// Clapeyron's theorem has it for a linear system loaded slowly from rest) and, at the steps the
// snapshot interval names (first and last by default), the ParaView files at t_k. The model ends
// in the final state.
#include "app/input/dem_parameters.h"
#include "dem/model/model.h"
#include "dem/solvers/static_solver.h"
#include <filesystem>

namespace dembridge::app
{
struct StaticRun
{
  dem::StaticResult last; ///< the final load step's solve
  double seconds = 0;     ///< assembly and solve, all steps
  int load_steps = 1;
};

/// Simulation/static linear solver as the settings every load step starts from: PETSc's GAMG
/// for large systems where the build has the fem layer (auto), always (gamg) or never (cg).
dem::StaticSettings static_solver_settings(dealii::ParameterHandler& prm);

/// `base`: the solver settings every step starts from (Simulation/static linear solver).
StaticRun run_static_load_steps(dem::Model& model, const dem::CaseConfig& config,
                                const OutputSettings& out, const std::filesystem::path& dir,
                                const dem::StaticSettings& base = {});

/// Sets every particle's group_mask bit g for the groups g < 32 it belongs to.
void assign_group_masks(dem::Model& model);

/// Names of the groups in bit order (at most 32): the group_mask's key in the ParaView files.
std::vector<std::string> group_names(const dem::Model& model);
} // namespace dembridge::app
