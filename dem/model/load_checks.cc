#include "dem/model/load_checks.h"
#include <string>

namespace dembridge::dem
{
std::uint8_t load_dofs(const Load& l)
{
  std::uint8_t components = 0; // bits x, y, z
  switch (l.kind)
  {
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
