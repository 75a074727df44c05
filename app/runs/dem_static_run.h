#pragma once
// A static DEM run (Simulation/solver = static) in load steps: Simulation/load steps solves the
// linear equilibrium for the loads at t_k = k T / N (T = Simulation/end time), the last step
// being the solver's final state (loads at full value, finite end times past; see
// dem/solvers/static_solver.h). Each step writes a history.csv row with the explicit run's
// columns (kinetic and damping energy zero; external work equal to the strain energy, as
// Clapeyron's theorem has it for a linear system loaded slowly from rest) and, at the steps the
// snapshot interval names (first and last by default), the ParaView files at t_k. The model ends
// in the final state. The same solves without files (solve_static_load_steps) and the figures
// of the final state serve the Python module's dembridge.Model, so that it gives the command
// line's figures to the bit.
#include "app/input/dem_parameters.h"
#include "app/output/dem_figures.h"
#include "app/output/dem_history.h"
#include "dem/model/model.h"
#include "dem/solvers/run_explicit.h"
#include "dem/solvers/static_solver.h"
#include <deal.II/base/parameter_handler.h>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

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
/// Under `mpirun -np N` (N > 1) a collective call on MPI_COMM_WORLD: rank 0 sends the case's
/// load steps and linear solver to the other ranks (solve_static_on_other_rank), and every
/// system, small and banded ones too, is solved by PETSc's CG on the N ranks together (GAMG; for
/// cg the Jacobi scaling alone), never factorised.
dem::StaticSettings static_solver_settings(dealii::ParameterHandler& prm);

/// Relative residual |b - A y| / |b| to which a run's iterative solves go (one rank and several),
/// tighter than the solver's 1e-10 default: the error of the figures is about this times the
/// condition number of the scaled system, and a run on N ranks (another multigrid hierarchy, other
/// round-off) is to give one rank's figures to 1e-10 relative. Measured on the HCP compression
/// (19 k unknowns): at 1e-10, one rank's Jacobi CG and two ranks' GAMG differ by 3e-10 in the
/// Poisson's ratios; see docs/parallel.md for the figures at this tolerance.
inline constexpr double static_solver_tolerance = 1e-13;

/// mpirun -np N, a rank other than 0: takes part in every load step's solve of rank 0's static
/// run (its load steps and linear solver received from rank 0's static_solver_settings); writes
/// nothing. The model ends in the final state, as on rank 0.
void solve_static_on_other_rank(dem::Model& model, const dem::CaseConfig& config);

/// Called after each load step @p k (1..N) at load time @p t, the model in that step's
/// equilibrium and its bond forces recorded.
using StaticStepDone = std::function<void(int k, double t, const dem::StaticResult& step)>;

/// The load steps' solves alone (no files): @p load_steps equilibria at t_k = k T / N, the last
/// the final state, each starting from @p base.
StaticRun solve_static_load_steps(dem::Model& model, const dem::CaseConfig& config, int load_steps,
                                  const dem::StaticSettings& base,
                                  const StaticStepDone& step_done = {});

/// `base`: the solver settings every step starts from (Simulation/static linear solver).
StaticRun run_static_load_steps(dem::Model& model, const dem::CaseConfig& config,
                                const OutputSettings& out, const std::filesystem::path& dir,
                                const dem::StaticSettings& base = {});

/// history.csv's row of load step @p k at load time @p t, the model in that step's equilibrium
/// (kinetic and damping energy zero, external work = strain energy: Clapeyron).
HistoryRecord static_step_record(const dem::Model& model, int k, double t);

/// summary.json's figures of a static run's solves: load steps, the deflection (returned in the
/// result beside the stop reason and the solver time), the geometry, the bond classes and the
/// solver's figures.
dem::RunResult add_static_run_figures(nlohmann::json& j, const dem::Model& model,
                                      const dem::CaseConfig& config, const StaticRun& run);

/// summary.json's figures of a DEM run's final state, static or explicit: the particle stresses
/// (@p stresses, of the model's current state), porosity, counts, time steps, the stop reason,
/// the deflection, the uniaxial and bending tests' moduli (fitted to @p history when the specimen
/// @p broke), the natural frequency and the groups.
void add_final_state_figures(nlohmann::json& j, const dem::Model& model,
                             const dem::CaseConfig& config, const std::string& bond_model,
                             const dem::RunResult& result, const dem::ParticleStresses& stresses,
                             const LoadHistory& history, bool broke);

/// Sets every particle's group_mask bit g for the groups g < 32 it belongs to.
void assign_group_masks(dem::Model& model);

/// Names of the groups in bit order (at most 32): the group_mask's key in the ParaView files.
std::vector<std::string> group_names(const dem::Model& model);
} // namespace dembridge::app
