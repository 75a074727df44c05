#pragma once
// A bonded-particle model built from a CaseConfig: particles, bonds, groups, supports, loads and
// the chosen time step, ready for ExplicitSolver.
#include "bond_store.h"
#include "case_config.h"
#include "groups.h"
#include "loads.h"
#include "particle_store.h"
#include "time_step.h"

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

  int group_index(const std::string& name, const std::string& where) const;
};

/// Builds the model; throws InputError naming the parameter at fault.
Model build_model(const CaseConfig& config);
} // namespace dembridge::dem
