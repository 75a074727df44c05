#pragma once
// The one reader of comma-separated numbers in case files ("0, 0.1, 2e-3"): vectors, corners,
// lists of offsets. Strict: every item a whole finite number, errors name where the text came
// from ("Section/key: 'text' is not a vector 'X,Y,Z'").
#include "dem/core/types.h"
#include <string>
#include <vector>

namespace dembridge::dem
{
/// Every comma-separated item of @p text as a double (empty items skipped); throws
/// std::runtime_error "@p where: 'ITEM' is not a number".
std::vector<double> parse_numbers(const std::string& text, const std::string& where);

/// Exactly three numbers "X,Y,Z"; throws std::runtime_error "@p where: 'TEXT' is not a vector
/// 'X,Y,Z'" otherwise.
Vec3 parse_vec3(const std::string& text, const std::string& where);
} // namespace dembridge::dem
