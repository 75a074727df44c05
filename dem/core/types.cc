#include "dem/core/types.h"
#include <sstream>

namespace dembridge::dem
{
std::uint8_t parse_dof_mask(const std::string& text, const std::string& where)
{
  static const char* names[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  std::uint8_t mask = 0;
  std::string token;
  std::stringstream ss(text);
  while (std::getline(ss, token, ','))
  {
    const auto b = token.find_first_not_of(" \t"), e = token.find_last_not_of(" \t");
    if (b == std::string::npos)
      continue;
    token = token.substr(b, e - b + 1);
    if (token == "all")
    {
      mask = 63;
      continue;
    }
    if (token == "none")
      continue;
    bool found = false;
    for (int k = 0; k < 6; ++k)
      if (token == names[k])
      {
        mask |= std::uint8_t(1u << k);
        found = true;
      }
    if (!found)
      throw InputError(where + ": unknown degree of freedom '" + token +
                       "' (expected ux, uy, uz, rx, ry, rz, all or none)");
  }
  return mask;
}
} // namespace dembridge::dem
