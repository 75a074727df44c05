#pragma once
// The `Contacts` and `Walls` sections of a DEM case file (dem/contacts/): the contact law for
// particles that touch without an intact bond, its constants, the neighbour search's skin, and
// the rigid walls, a named list like the groups: `Walls/names = bottom, top` declares the
// subsections `Wall bottom` and `Wall top`. Values are checked by ContactConfig::validate and
// WallConfig::validate (one-line InputError naming Contacts/key or Wall NAME/key).
#include "dem/model/case_config.h"
#include <deal.II/base/parameter_handler.h>
#include <string>
#include <vector>

namespace dembridge::app
{
/// Declares `Contacts` and `Walls` (its `names`).
void declare_contact_parameters(dealii::ParameterHandler& prm);
/// Declares `Wall NAME` for the given names.
void declare_wall_parameters(dealii::ParameterHandler& prm, const std::vector<std::string>& names);
/// Reads both sections into c.contacts and c.walls.
void parse_contact_parameters(dealii::ParameterHandler& prm, dem::CaseConfig& c);
} // namespace dembridge::app
