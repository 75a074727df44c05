#include "dem/microstructure/microstructure.h"
#include <cmath>
#include <numbers>
#include <sstream>

namespace dembridge::dem
{
namespace
{
std::string number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

/// A class's friction angle, moment factor and fracture energies as Damage checks its own
/// (bond_strength.cc), named in the class's section.
void check_failure_constants(const BondClassConfig& c, const DamageConfig& damage,
                             const std::string& where)
{
  auto refuse = [&](const char* key, double v, const char* why)
  { throw InputError(where + "/" + key + ": " + why + " (got " + number(v) + ")"); };
  if (damage.law.shear == ShearCriterion::mohr_coulomb &&
      !(c.friction_angle >= 0 && c.friction_angle < 90))
    refuse("friction angle", c.friction_angle, "must lie in [0, 90) degrees");
  if (!(c.moment_factor >= 0 && c.moment_factor <= 1))
    refuse("moment factor", c.moment_factor, "must lie in [0, 1]");
  if (damage.law.mode == FailureMode::softening)
    for (auto [g, key] : {std::pair{c.fracture_energy_I, "fracture energy mode I"},
                          std::pair{c.fracture_energy_II, "fracture energy mode II"}})
      if (!(g > 0) || !std::isfinite(g))
        refuse(key, g, "softening needs a positive fracture energy, J/m^2");
}

std::string section(BondClass c)
{
  return c == BondClass::intra_grain ? "Bonds" : "Bond class " + std::string(bond_class_name(c));
}
} // namespace

BondClassConfig BondClassConfig::of_specimen(const BondMaterial& material,
                                             const DamageConfig& damage)
{
  return {material,
          damage.tensile_strength,
          damage.shear_strength,
          damage.cohesion,
          damage.friction_angle,
          damage.law.moment_factor,
          damage.law.fracture_energy_I,
          damage.law.fracture_energy_II};
}

std::array<BondClassConfig, bond_class_count> bond_class_configs(const MicrostructureConfig& config,
                                                                 const BondMaterial& material,
                                                                 const DamageConfig& damage)
{
  damage.validate(); // the specimen's own strengths first: the classes default to them
  const BondClassConfig bulk = BondClassConfig::of_specimen(material, damage);
  std::array<BondClassConfig, bond_class_count> classes{bulk, config.grain_boundary.value_or(bulk),
                                                        config.weak_plane.value_or(bulk),
                                                        config.basal.value_or(bulk)};
  for (std::size_t k = 1; k < bond_class_count; ++k)
  {
    const std::string where = section(BondClass(k));
    classes[k].material.validate(where);
    if (damage.law.mode == FailureMode::none)
      continue;
    auto require = [&](double v, const char* key)
    {
      if (!(v > 0) || !std::isfinite(v))
        throw InputError(where + "/" + key + ": must be positive when Damage/failure is on (got " +
                         number(v) + " Pa): the class has no strength");
    };
    require(classes[k].tensile_strength, "tensile strength");
    if (damage.law.shear == ShearCriterion::constant)
      require(classes[k].shear_strength, "shear strength");
    else
      require(classes[k].cohesion, "cohesion");
    check_failure_constants(classes[k], damage, where);
  }
  return classes;
}

std::array<ClassDamage, bond_class_count>
class_damage(const std::array<BondClassConfig, bond_class_count>& classes,
             const DamageConfig& damage)
{
  std::array<ClassDamage, bond_class_count> out;
  for (std::size_t k = 0; k < bond_class_count; ++k)
  {
    const BondClassConfig& c = classes[k];
    FailureConstants law{std::tan(c.friction_angle * std::numbers::pi / 180), c.moment_factor,
                         c.fracture_energy_I, c.fracture_energy_II};
    if (damage.law.shear != ShearCriterion::mohr_coulomb)
      law.tan_friction = damage.law.tan_friction; // as assign_bond_strengths leaves the law's
    out[k] = {c.tensile_strength,
              damage.law.shear == ShearCriterion::constant ? c.shear_strength : c.cohesion, law};
  }
  return out;
}

MicrostructureSummary
apply_microstructure(ParticleStore& p, BondStore& b, const MicrostructureConfig& config,
                     const std::array<BondClassConfig, bond_class_count>& classes)
{
  MicrostructureSummary summary;
  if (!config.enabled())
    return summary;
  const std::size_t n = p.size(), nb = b.size();
  if (config.grains.enabled)
  {
    GrainMap map = assign_grains(p.reference_position, p.radius, config.grains);
    p.grain = std::move(map.of_particle);
    summary.grains = std::move(map.grains);
    summary.columns = map.columns;
    if (config.boundary_joint_friction)
    {
      if (!b.sliding_joints) // no plane offsets: no pair lies across a plane
        b.sliding_joints = SlidingJoints{};
      b.sliding_joints->boundary_friction = *config.boundary_joint_friction;
      for (const Grain& g : summary.grains)
        b.sliding_joints->grain_seed.push_back(g.seed);
    }
  }
  std::optional<WeakPlaneSet> planes = config.weak_planes;
  std::vector<std::size_t> crossing; // bonds per plane offset
  if (planes)
  {
    double mean_radius = 0;
    for (double r : p.radius)
      mean_radius += r / double(n);
    check_weak_planes(*planes, 2 * mean_radius, "Microstructure/");
    crossing.assign(planes->offsets.size(), 0);
    if (config.smooth_joint)
    {
      b.smooth_joint_normal = planes->normal; // unit (check_weak_planes)
      if (!b.sliding_joints) // the grains' boundaries, if they slide, are in already
        b.sliding_joints = SlidingJoints{};
      SlidingJoints& joints = *b.sliding_joints;
      joints.normal = planes->normal, joints.offsets = planes->offsets;
      joints.spacing = planes->spacing, joints.friction = config.joint_friction;
    }
  }
  b.bond_class.assign(nb, BondClass::intra_grain);
  const bool basal = config.basal_cone > 0 && !p.grain.empty();
  const double basal_cos = std::cos(config.basal_cone * std::numbers::pi / 180);
  if (basal && config.basal_smooth_joint)
    b.basal_normal.assign(nb, Vec3::Zero());
  for (std::size_t k = 0; k < nb; ++k)
  {
    const int i = b.a[k], j = b.b[k];
    BondClass c = BondClass::intra_grain;
    if (!p.grain.empty() && p.grain[std::size_t(i)] != p.grain[std::size_t(j)])
      c = BondClass::grain_boundary;
    else if (basal)
    {
      const Vec3& c_axis = summary.grains[std::size_t(p.grain[std::size_t(i)])].c_axis;
      if (std::abs(b.rest_axis[k].dot(c_axis)) >= basal_cos)
      {
        c = BondClass::basal;
        if (!b.basal_normal.empty())
          b.basal_normal[k] = c_axis;
      }
    }
    if (planes)
    {
      const PlaneCrossing x = crossed_planes(*planes, p.reference_position[std::size_t(i)],
                                             p.reference_position[std::size_t(j)]);
      if (x.count > 0)
        c = BondClass::weak_plane, ++crossing[std::size_t(x.offset)];
    }
    b.bond_class[k] = c;
    ++summary.bonds_per_class[std::size_t(c)];
    if (c == BondClass::intra_grain)
      continue;
    // the class's constants, as add_bond computes them from the Bonds material
    const BondMaterial& mat = classes[std::size_t(c)].material;
    const BondStiffness s =
        bond_stiffness(mat, b.rest_length[k], p.radius[std::size_t(i)], p.radius[std::size_t(j)]);
    b.kn[k] = s.kn, b.ks[k] = s.ks, b.ktor[k] = s.ktor, b.kben[k] = s.kben;
    b.contact_fraction[k] = s.contact_fraction, b.radius[k] = s.radius;
    b.model[k] = mat.model;
  }
  for (std::size_t m = 0; m < crossing.size(); ++m)
    if (crossing[m] == 0)
      throw InputError("Microstructure/weak plane offsets: the plane" +
                       std::string(planes->spacing > 0 ? "s" : "") + " at " +
                       number(planes->offsets[m]) + " m" +
                       (planes->spacing > 0 ? " (every " + number(planes->spacing) + " m)" : "") +
                       " cross" + (planes->spacing > 0 ? "" : "es") +
                       " no bond: outside the specimen, or between unbonded particles");
  return summary;
}
} // namespace dembridge::dem
