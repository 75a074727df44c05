#include "dem/model/load_checks.h"
#include <algorithm>
#include <cmath>
#include <string>

namespace dembridge::dem
{
std::uint8_t load_dofs(const Load& l)
{
  std::uint8_t components = 0; // bits x, y, z
  switch (l.kind)
  {
  case LoadKind::pressure: // along its direction, whenever it may push
    if (l.pressure == 0 && l.ratio == 0)
      break;
    [[fallthrough]];
  case LoadKind::force:
  case LoadKind::moment:
    for (int d = 0; d < 3; ++d)
      components |= std::uint8_t(l.value[d] != 0 ? 1u << d : 0u);
    break;
  case LoadKind::velocity:
  case LoadKind::angular_velocity:
  case LoadKind::displacement:
    components = l.components;
    break;
  }
  const bool rotation = l.kind == LoadKind::moment || l.kind == LoadKind::angular_velocity;
  return std::uint8_t(rotation ? components << 3 : components);
}

void check_pressure_loads(const CaseConfig& c, Model& m)
{
  for (std::size_t k = 0; k < m.loads.size(); ++k)
  {
    Load& l = m.loads[k];
    if (l.kind != LoadKind::pressure)
      continue;
    const std::string where = "Load " + l.name;
    if (!(l.area > 0) || !std::isfinite(l.area))
      throw InputError(where + "/area: a pressure needs the positive area of its face (m^2)");
    if (!(l.value.norm() > 0))
      throw InputError(where + "/value: a pressure needs the direction it pushes (non-zero)");
    l.value.normalize();
    if (!std::isfinite(l.pressure) || !std::isfinite(l.ratio))
      throw InputError(where + "/pressure: must be finite");
    const std::string& ref = c.loads[k].ratio_load;
    if (ref.empty())
    {
      if (l.ratio != 0)
        throw InputError(where + "/ratio load: a ratio needs the load whose stress it follows");
      continue;
    }
    const auto found =
        std::find_if(m.loads.begin(), m.loads.end(), [&](const Load& o) { return o.name == ref; });
    if (found == m.loads.end())
      throw InputError(where + "/ratio load: no load named '" + ref + "'");
    if (!found->prescribes_motion() || found->kind == LoadKind::angular_velocity)
      throw InputError(where + "/ratio load: '" + ref +
                       "' must prescribe a displacement or velocity (its reaction is the stress)");
    if (!(found->area > 0))
      throw InputError("Load " + ref + "/area: the load '" + l.name +
                       "' follows needs the positive area its reaction acts on (m^2)");
    if (!(found->value.norm() > 0))
      throw InputError("Load " + ref + "/value: the load '" + l.name +
                       "' follows needs a non-zero value (its direction)");
    l.ratio_load = int(found - m.loads.begin());
  }
}

void check_loads_act_on_free_dofs(const Model& m)
{
  std::vector<std::uint8_t> fixed(m.particles.size(), 0);
  for (const auto& c : m.constraints)
    for (int i : m.groups[std::size_t(c.group)].members)
      fixed[std::size_t(i)] |= c.dofs;
  static const char* names[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  for (const auto& l : m.loads)
  {
    const std::uint8_t dofs = load_dofs(l);
    if (dofs == 0)
      continue; // a zero load acts on nothing; nothing to refuse
    const auto& g = m.groups[std::size_t(l.group)];
    bool free = false;
    for (int i : g.members)
      free = free || (dofs & ~fixed[std::size_t(i)]) != 0;
    if (free)
      continue;
    std::string list;
    for (int k = 0; k < 6; ++k)
      if (dofs & (1u << k))
        list += (list.empty() ? "" : ", ") + std::string(names[k]);
    throw InputError("Load " + l.name + "/group: every DOF the load acts on (" + list +
                     ") is held by a support on every particle of group '" + g.name +
                     "', so the load would only " +
                     (l.prescribes_motion() ? "fight the support" : "load the support"));
  }
}
} // namespace dembridge::dem
