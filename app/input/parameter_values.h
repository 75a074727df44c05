#pragma once
// Values of case-file entries that the input sections share: the pattern of an "x, y, z" entry,
// the readers of vectors and number lists (dem/core/number_list.h) by key, and the names a
// named-section list (`Groups/names = left, tip`) declares.
#include "app/input/dem_parameters.h"
#include "dem/core/number_list.h"
#include <deal.II/base/parameter_handler.h>
#include <limits>
#include <stdexcept>
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

/// The entry `end time` of the current subsection `@p where` (a load, a wall): 'inf' or 'never'
/// is never, anything else must be a number of seconds.
inline double get_end_time(dealii::ParameterHandler& prm, const std::string& where)
{
  const std::string end = prm.get("end time");
  if (end == "inf" || end == "never")
    return std::numeric_limits<double>::infinity();
  try
  {
    // the strict reader: the whole entry must be the one number ("1e-3x" is not)
    if (const auto value = dem::parse_numbers(end, where + "/end time"); value.size() == 1)
      return value[0];
  }
  catch (const std::exception&)
  {
  }
  throw dem::InputError(where + "/end time: '" + end + "' is neither 'inf' nor a number");
}

/// The names listed in `SECTION/names` (Groups, Loads, Walls), in their order: each names a
/// subsection `Group NAME`, `Load NAME` or `Wall NAME`.
inline std::vector<std::string> listed_names(dealii::ParameterHandler& prm,
                                             const std::string& section)
{
  prm.enter_subsection(section);
  auto names = split_names(prm.get("names"));
  prm.leave_subsection();
  return names;
}
} // namespace dembridge::app
