#pragma once
// The `Damage` section of a DEM case file: bond strengths, their scatter and the failure law
// (dem/bonds/bond_strength.h, bond_damage.h), declared with defaults and documentation and read
// into dem::DamageConfig. The values are checked by DamageConfig::validate and, for the
// fracture energies against snap-back, by assign_bond_strengths (one-line InputError naming
// Damage/key).
#include "dem/bonds/bond_strength.h"
#include <deal.II/base/parameter_handler.h>

namespace dembridge::app
{
void declare_damage_parameters(dealii::ParameterHandler& prm);
dem::DamageConfig parse_damage_parameters(dealii::ParameterHandler& prm);
} // namespace dembridge::app
