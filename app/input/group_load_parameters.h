#pragma once
// The named sections of a DEM case: `Groups/names = left, tip` declares the subsections
// `Group left` and `Group tip` (which particles, what is held, their mass and initial velocity),
// `Loads/names` the subsections `Load NAME` (what acts on a group, how it ramps and ends).
#include "dem/model/case_config.h"
#include <deal.II/base/parameter_handler.h>
#include <string>
#include <vector>

namespace dembridge::app
{
/// Declares `Group NAME` / `Load NAME` subsections for the given names.
void declare_group_parameters(dealii::ParameterHandler& prm, const std::vector<std::string>& names);
void declare_load_parameters(dealii::ParameterHandler& prm, const std::vector<std::string>& names);

/// The groups named in Groups/names, in that order, each read from its `Group NAME` section;
/// throws dem::InputError (Group NAME/key: reason).
std::vector<dem::GroupConfig> parse_group_sections(dealii::ParameterHandler& prm);

/// The loads named in Loads/names, in that order, each read from its `Load NAME` section;
/// throws dem::InputError (Load NAME/key: reason).
std::vector<dem::LoadConfig> parse_load_sections(dealii::ParameterHandler& prm);
} // namespace dembridge::app
