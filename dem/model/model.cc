#include "dem/model/model.h"
#include "dem/bonds/bonding.h"
#include "dem/contacts/contact_forces.h"
#include "dem/model/load_checks.h"
#include "dem/model/renumbering.h"
#include "dem/packing/packings.h"
#include <numbers>
#include <sstream>

namespace dembridge::dem
{
int Model::group_index(const std::string& name, const std::string& where) const
{
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (groups[g].name == name)
      return int(g);
  std::string known;
  for (const auto& g : groups)
    known += (known.empty() ? "" : ", ") + g.name;
  throw InputError(where + ": no group named '" + name +
                   "' (groups: " + (known.empty() ? "none" : known) + ")");
}

namespace
{
/// Porosity of the packing; optionally scales the particle density by it (thesis eq. 63).
void set_porosity(const ParticleSource& src, Model& m)
{
  using K = ParticleSource::Kind;
  auto& p = m.particles;
  // A random packing fills its box up to the walls; a lattice is measured by its own extent
  // (thesis Table 2: the HCP specimen of r = 5 mm is 0.255 x 0.0995 x 0.0998 m), which is also
  // the cross-section the measurements use.
  if (src.kind == K::random)
    m.packing_volume = src.box_size.prod();
  else
  {
    const auto [lo, hi] = reference_extent(p);
    m.packing_volume = (hi - lo).prod();
  }
  double solid = 0;
  for (double r : p.radius)
    solid += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  m.porosity = m.packing_volume > 0 ? 1.0 - solid / m.packing_volume : 0.0;
  if (src.scale_density_by_porosity)
  {
    if (!(m.porosity >= 0 && m.porosity < 1))
      throw InputError("Particles/scale density by porosity: the packing's porosity " +
                       std::to_string(m.porosity) + " is outside [0, 1)");
    for (std::size_t i = 0; i < p.size(); ++i)
      p.set_mass(i, p.mass[i] / (1.0 - m.porosity));
  }
}
} // namespace

Model build_model(const CaseConfig& c)
{
  Model m;
  generate_particles(c.particles, m.particles, c.run.threads);
  auto& p = m.particles;
  set_porosity(c.particles, m);
  if (c.particles.keep)
  {
    keep_particles(p, c.particles.keep);
    if (p.size() == 0)
      throw InputError("Particles: the particle region holds no particle centre of the packing");
  }

  c.bonds.material.validate("Bonds");
  if (!c.run.bond_force_records) // before formation, so that the store never holds them
    m.bonds.drop_force_records();
  if (c.bonds.explicit_bonds.empty())
    form_bonds(p, m.bonds, c.bonds.material, c.bonds.contact_radius_multiplier);
  else
  {
    for (auto [i, j] : c.bonds.explicit_bonds)
      add_bond(p, m.bonds, c.bonds.material, i, j);
    mark_reference_configuration(p);
  }
  if (m.bonds.size() == 0 && !c.contacts.enabled() && p.size() == 1)
    throw InputError("Particles: the case has one particle, and a bonded model needs at least "
                     "two (no bond can form)");
  if (m.bonds.size() == 0 && !c.contacts.enabled()) // contacts alone make a granular model
    throw InputError("Bonds: no bond was formed (contact radius multiplier " +
                     std::to_string(c.bonds.contact_radius_multiplier) +
                     " too small for the particle spacing?)");
  // Strengths in formation order, before any solver reorders the bonds: the same seed gives
  // the same strength to the same pair whatever the thread count.
  if (c.damage.law.mode != FailureMode::none && c.run.static_solver)
    throw InputError("Damage/failure: the static solver solves the linear, undamaged bond "
                     "network; bond failure needs Simulation/solver = explicit");
  std::array<ClassDamage, bond_class_count> class_damages{};
  if (c.microstructure.enabled()) // grains and bond classes, before the strengths they pick
  {
    const auto classes = bond_class_configs(c.microstructure, c.bonds.material, c.damage);
    m.microstructure = apply_microstructure(p, m.bonds, c.microstructure, classes);
    class_damages = class_damage(classes, c.damage);
  }
  assign_bond_strengths(m.bonds, c.damage, &m.particles.reference_position,
                        c.microstructure.enabled() ? std::span<const ClassDamage>(class_damages)
                                                   : std::span<const ClassDamage>());

  if (c.groups.size() > 32)
    throw InputError("Groups/names: at most 32 groups");
  for (const auto& gc : c.groups)
  {
    const std::string where = "Group " + gc.name;
    for (const auto& g : m.groups)
      if (g.name == gc.name)
        throw InputError("Groups/names: group '" + gc.name + "' is named twice");
    m.groups.push_back(select_group(p, gc.name, gc.selection, where + "/select"));
    const int gi = int(m.groups.size()) - 1;
    if (gc.mass < 0)
      throw InputError(where + "/mass: must be positive, or 0 to keep density * volume");
    for (int i : m.groups.back().members)
    {
      if (gc.mass > 0)
        p.set_mass(i, gc.mass);
      p.velocity[i] = gc.initial_velocity;
    }
    if (gc.fixed)
      m.constraints.push_back({gi, gc.fixed});
  }
  for (const auto& lc : c.loads)
  {
    Load l = lc.load;
    const std::string where = "Load " + l.name;
    l.group = m.group_index(lc.group, where + "/group");
    if (l.ramp_time < 0)
      throw InputError(where + "/ramp time: must not be negative");
    if (!(l.end_time > 0))
      throw InputError(where + "/end time: must be positive");
    if (!l.value.allFinite())
      throw InputError(where + "/value: must be finite");
    if (l.kind == LoadKind::displacement && !(l.ramp_time > 0) && !c.run.static_solver)
      throw InputError(where + "/ramp time: an explicit run needs a displacement load to ramp " +
                       "over a positive time (a jump is an infinite velocity)");
    m.loads.push_back(l);
  }
  check_pressure_loads(c, m);
  check_loads_act_on_free_dofs(m);
  // Spatial order (renumbering.h) of the built specimen: strengths, groups and explicit bonds
  // were resolved in the user's numbering, and move with their particles and bonds; outputs
  // show ParticleStore::id. Everything after this point (damping, time step, contacts, the
  // solvers, a coupling's interface particles) sees the new indices.
  if (c.spatial_order)
    renumber_spatially(p, m.bonds, &m.groups);

  assign_bond_damping(p, m.bonds, c.run.bond_damping_ratio);
  m.critical = estimate_critical_time_step(p, m.bonds, c.run.particle_damping);
  if (c.contacts.enabled() || !c.walls.empty())
  {
    if (c.run.static_solver)
      throw InputError("Contacts/model: the static solver solves the bond network alone; "
                       "contacts and walls need Simulation/solver = explicit");
    std::vector<WallConfig> walls = c.walls;
    place_touching_walls(walls, p);
    auto contacts = std::make_shared<ContactForces>(c.contacts, walls);
    m.critical.contact_bound =
        contacts->critical_time_step(p) / std::sqrt(1.0 + c.run.particle_damping);
    if (!c.contacts.platens.empty())
    {
      // cross-section of the specimen normal to the platens (the particles' extent)
      std::vector<int> index;
      for (const auto& name : c.contacts.platens)
        for (std::size_t w = 0; w < c.walls.size(); ++w)
          if (c.walls[w].name == name)
            index.push_back(int(w));
      if (c.contacts.platens.size() != 2 || index.size() != 2)
        throw InputError("Contacts/platens: expected the names of two walls 'lower, upper'");
      const auto [lo, hi] = reference_extent(p);
      int axis;
      walls[std::size_t(index[0])].normal.cwiseAbs().maxCoeff(&axis);
      const Vec3 size = hi - lo;
      contacts->measure_platens(index[0], index[1], size.prod() / size[axis]);
    }
    m.contributions.push_back(contacts);
  }
  if (c.run.time_step > 0)
  {
    if (c.run.time_step > m.critical.critical())
    {
      std::ostringstream s;
      s << "Simulation/time step: " << c.run.time_step << " s is above the stability limit "
        << m.critical.critical() << " s of this bond network (use 'auto' or a smaller step)";
      throw InputError(s.str());
    }
    m.time_step = c.run.time_step;
  }
  else
  {
    if (!(c.run.safety > 0 && c.run.safety <= 1))
      throw InputError("Simulation/time step safety: must lie in (0, 1]");
    m.time_step = c.run.safety * m.critical.critical();
  }
  return m;
}
} // namespace dembridge::dem
