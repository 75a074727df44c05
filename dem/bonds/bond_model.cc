#include "dem/bonds/bond_model.h"
#include <algorithm>
#include <numbers>
#include <sstream>

namespace dembridge::dem
{
BondModel bond_model_from_name(std::string_view name)
{
  for (std::size_t i = 0; i < bond_model_names.size(); ++i)
    if (bond_model_names[i] == name)
      return static_cast<BondModel>(i);
  throw InputError("unknown bond model '" + std::string(name) + "' (expected one of " +
                   bond_model_selection() + ")");
}

std::string bond_model_selection()
{
  std::string s;
  for (auto n : bond_model_names)
    s += (s.empty() ? "" : "|") + std::string(n);
  return s;
}

void BondMaterial::validate(const std::string& section) const
{
  auto fail = [&](const std::string& key, const std::string& why)
  { throw InputError(section + "/" + key + ": " + why); };
  if (!(youngs_modulus > 0))
    fail("youngs modulus", "must be positive (got " + std::to_string(youngs_modulus) + " Pa)");
  if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5))
    fail("poisson ratio", "must lie in (-1, 0.5) for an isotropic solid (got " +
                              std::to_string(poisson_ratio) + ")");
  if (!(radius_multiplier > 0))
    fail("radius multiplier", "must be positive (got " + std::to_string(radius_multiplier) + ")");
  if (stiffness_ratio < 0)
    fail("stiffness ratio", "must be positive, or 0 for 2(1+nu)");
  if (normal_stiffness_per_area < 0)
    fail("normal stiffness per area", "must be positive, or 0 for E_b/L_b");
}

BondStiffness bond_stiffness(const BondMaterial& mat, double L, double ra, double rb)
{
  const double pi = std::numbers::pi;
  const double E = mat.youngs_modulus, nu = mat.poisson_ratio;
  BondStiffness k;
  k.radius = mat.radius_multiplier * std::min(ra, rb);
  const double r = k.radius;
  const double A = pi * r * r;                // eq. 23
  const double I = 0.25 * pi * r * r * r * r; // eq. 24
  k.kn = E * A / L;                           // Table 9
  k.kben = 0.25 * k.kn * r * r;               // Table 9
  switch (mat.model)
  {
  case BondModel::parallel_bond:
  {
    if (mat.normal_stiffness_per_area > 0)
    {
      k.kn = mat.normal_stiffness_per_area * A; // thesis eq. 10
      k.kben = 0.25 * k.kn * r * r;             // = k̄_n I (thesis eq. 17)
    }
    const double kappa = mat.stiffness_ratio > 0 ? mat.stiffness_ratio : 2.0 * (1.0 + nu); // eq. 8
    k.ks = k.kn / kappa;
    k.ktor = 0.5 * k.ks * r * r;                  // Table 1 (= k̄_s J)
    k.contact_fraction = 0.5 * (L + ra - rb) / L; // Table 9
    break;
  }
  case BondModel::euler_bernoulli:
    k.ks = 12.0 * E * I / (L * L * L);         // eq. 26
    k.ktor = 0.25 * k.kn * r * r / (1.0 + nu); // Table 6
    break;
  case BondModel::timoshenko:
  {
    const double phi = 20.0 * r * r * (1.0 + nu) / (3.0 * L * L); // eq. 25
    k.ks = 12.0 * E * I / (L * L * L * (1.0 + phi));              // eq. 18
    k.ktor = 0.25 * k.kn * r * r / (1.0 + nu);                    // Table 6
    break;
  }
  }
  return k;
}
} // namespace dembridge::dem
