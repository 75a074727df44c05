#pragma once
// A bonded-particle model built from a CaseConfig: particles, bonds, groups, supports, loads and
// the chosen time step, ready for ExplicitSolver.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/model/case_config.h"
#include "dem/model/groups.h"
#include "dem/model/loads.h"
#include "dem/solvers/step_contribution.h"
#include "dem/solvers/time_step.h"
#include <memory>

namespace dembridge::dem
{
struct Model
{
  ParticleStore particles;
  BondStore bonds;
  std::vector<Group> groups;
  std::vector<Constraint> constraints;
  std::vector<Load> loads;
  TimeStepEstimate critical;
  double time_step = 0;
  double packing_volume = 0; ///< m^3: the box of a random packing, else the particles' extent
  double porosity = 0;       ///< 1 - sum of sphere volumes / packing_volume
  /// grains (seeds, c-axes) and bonds per class; empty without a microstructure
  MicrostructureSummary microstructure;
  /// Forces beside the bonds (contacts, walls), attached to the explicit solver by run_explicit.
  std::vector<std::shared_ptr<StepContribution>> contributions;

  int group_index(const std::string& name, const std::string& where) const;
};

/// Builds the model; throws InputError naming the parameter at fault.
Model build_model(const CaseConfig& config);
} // namespace dembridge::dem
