#pragma once
// Values of case-file entries that the input sections share: the pattern of an "x, y, z" entry
// and the readers of vectors and number lists (dem/core/number_list.h) by key.
#include "dem/core/number_list.h"
#include <deal.II/base/parameter_handler.h>
#include <string>
#include <vector>

namespace dembridge::app
{
/// Pattern of an entry holding three numbers "x, y, z".
inline const dealii::Patterns::List vector3(dealii::Patterns::Double(), 3, 3);

/// The entry @p key of the current subsection as a vector.
inline dem::Vec3 get_vec3(dealii::ParameterHandler& prm, const std::string& key)
{
  return dem::parse_vec3(prm.get(key), key);
}

/// The entry @p key of the current subsection as a list of numbers.
inline std::vector<double> get_doubles(dealii::ParameterHandler& prm, const std::string& key)
{
  return dem::parse_numbers(prm.get(key), key);
}
} // namespace dembridge::app
