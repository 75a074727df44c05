#include "dem/core/number_list.h"
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace dembridge::dem
{
namespace
{
std::string trimmed(const std::string& s)
{
  const auto first = s.find_first_not_of(" \t\n\r");
  if (first == std::string::npos)
    return "";
  return s.substr(first, s.find_last_not_of(" \t\n\r") - first + 1);
}
} // namespace

std::vector<double> parse_numbers(const std::string& text, const std::string& where)
{
  std::vector<double> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
  {
    item = trimmed(item);
    if (item.empty())
      continue;
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(item.c_str(), &end);
    if (end != item.c_str() + item.size() || !std::isfinite(value) ||
        (errno == ERANGE && std::abs(value) > 1))
      throw std::runtime_error(where + ": '" + item + "' is not a number");
    values.push_back(value);
  }
  return values;
}

Vec3 parse_vec3(const std::string& text, const std::string& where)
{
  std::size_t items = 0;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    items += trimmed(item).empty() ? 0 : 1;
  if (items != 3)
    throw std::runtime_error(where + ": '" + text + "' is not a vector 'X,Y,Z'");
  const auto v = parse_numbers(text, where);
  return {v[0], v[1], v[2]};
}
} // namespace dembridge::dem
