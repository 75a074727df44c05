#include "dem/contacts/contact_config.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace dembridge::dem
{
ContactModel contact_model_from_name(std::string_view name)
{
  for (std::size_t k = 0; k < contact_model_names.size(); ++k)
    if (contact_model_names[k] == name)
      return ContactModel(k);
  throw InputError("Contacts/model: unknown contact model '" + std::string(name) + "' (" +
                   contact_model_selection() + ")");
}

std::string contact_model_selection()
{
  std::string s;
  for (auto name : contact_model_names)
    s += (s.empty() ? "" : "|") + std::string(name);
  return s;
}

double ContactConfig::damping_ratio() const
{
  if (!(restitution < 1))
    return 0.0;
  const double l = std::log(restitution);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

void ContactConfig::validate() const
{
  if (!enabled())
    return;
  if (model == ContactModel::linear && !(normal_stiffness > 0))
    throw InputError("Contacts/normal stiffness: the linear contact law needs a positive normal "
                     "stiffness (N/m)");
  if (model == ContactModel::linear && tangential_stiffness < 0)
    throw InputError("Contacts/tangential stiffness: must not be negative (0: 2/7 of the normal "
                     "stiffness)");
  if (model == ContactModel::hertz_mindlin && !(youngs_modulus > 0))
    throw InputError("Contacts/youngs modulus: the Hertz-Mindlin law needs the particles' "
                     "positive Young's modulus (Pa)");
  if (model == ContactModel::hertz_mindlin && !(poisson_ratio > -1 && poisson_ratio < 0.5))
    throw InputError("Contacts/poisson ratio: must lie in (-1, 0.5)");
  if (!(restitution > 0 && restitution <= 1))
    throw InputError("Contacts/restitution coefficient: must lie in (0, 1]");
  if (!(friction >= 0) || !std::isfinite(friction))
    throw InputError("Contacts/friction coefficient: must not be negative");
  if (!(rolling_friction >= 0) || !std::isfinite(rolling_friction))
    throw InputError("Contacts/rolling friction: must not be negative");
  if (!(rolling_stiffness >= 0))
    throw InputError("Contacts/rolling stiffness: must not be negative (0: 2.25 k_n mu_r^2 R*^2)");
  if (!(skin >= 0) || !std::isfinite(skin))
    throw InputError("Contacts/skin: must not be negative (0: a fifth of the smallest radius)");
  if (!(reference_tensile_strength >= 0) || !std::isfinite(reference_tensile_strength))
    throw InputError("Contacts/reference tensile strength: must not be negative (0: none)");
  if (reference_tensile_strength > 0 && platens.empty())
    throw InputError("Contacts/reference tensile strength: the strength ratio needs a platen "
                     "test (Contacts/platens)");
}

void WallConfig::validate() const
{
  const std::string where = "Wall " + name;
  if (!point.allFinite())
    throw InputError(where + "/point: must be finite");
  if (!normal.allFinite() || !(normal.norm() > 0))
    throw InputError(where + "/normal: must be a non-zero vector");
  if (!velocity.allFinite())
    throw InputError(where + "/velocity: must be finite");
  if (!(ramp_time >= 0))
    throw InputError(where + "/ramp time: must not be negative");
  if (!(end_time > 0))
    throw InputError(where + "/end time: must be positive");
}

void place_touching_walls(std::vector<WallConfig>& walls, const ParticleStore& p)
{
  for (auto& w : walls)
  {
    if (!w.touch || p.size() == 0)
      continue;
    const Vec3 n = w.normal.normalized();
    double gap = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i)
      gap = std::min(gap, (p.position[i] - w.point).dot(n) - p.radius[i]);
    w.point += gap * n;
  }
}
} // namespace dembridge::dem
