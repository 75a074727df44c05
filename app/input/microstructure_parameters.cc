#include "app/input/microstructure_parameters.h"
#include "app/input/parameter_values.h"
#include <sstream>

namespace dembridge::app
{
using dealii::ParameterHandler;
using dealii::Patterns::Anything;
using dealii::Patterns::Bool;
using dealii::Patterns::Double;
using dealii::Patterns::Integer;
using dealii::Patterns::List;
using dealii::Patterns::Selection;
namespace dem = dembridge::dem;

namespace
{
/// The classes a case file names, with the keys each takes over from Bonds or Damage.
const char* const class_sections[] = {"Bond class grain_boundary", "Bond class weak_plane",
                                      "Bond class basal"};

/// @p key's number, or @p fallback when it is empty.
double number_or(ParameterHandler& prm, const std::string& section, const std::string& key,
                 double fallback, bool& set)
{
  const std::string text = prm.get(key);
  if (text.find_first_not_of(" \t") == std::string::npos)
    return fallback;
  set = true;
  try
  {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (text.find_first_not_of(" \t", used) == std::string::npos)
      return v;
  }
  catch (const std::exception&)
  {
  }
  throw dem::InputError(section + "/" + key + ": '" + text +
                        "' is not a number (leave it empty for the Bonds or Damage value)");
}

bool blank(const std::string& text)
{
  return text.find_first_not_of(" \t") == std::string::npos;
}

/// The weak-plane class's joint friction (in its section), or @p fallback when it is empty; set
/// while @p smooth (its smooth joint) is false, it is refused: nothing would read it.
double joint_friction(ParameterHandler& prm, const std::string& section, bool smooth,
                      double fallback)
{
  const std::string key = "joint friction", text = prm.get(key);
  if (text.find_first_not_of(" \t") == std::string::npos)
    return fallback;
  double v = 0;
  std::size_t used = 0;
  try
  {
    v = std::stod(text, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (used == 0 || text.find_first_not_of(" \t", used) != std::string::npos)
    throw dem::InputError(section + "/" + key + ": '" + text + "' is not a number");
  if (!(v >= 0))
    throw dem::InputError(section + "/" + key + ": must not be negative (got " + text + ")");
  if (!smooth)
    throw dem::InputError(section + "/" + key + ": set, but " + section +
                          "/smooth joint is false: only smooth joints slide on the plane with "
                          "this friction (set smooth joint = true, or leave it empty)");
  return v;
}
} // namespace

void declare_microstructure_parameters(ParameterHandler& prm)
{
  prm.enter_subsection("Microstructure");
  prm.declare_entry("grains", "none", Selection("none|columnar"),
                    "none: no grains; columnar: columns from a 2-D Voronoi tessellation of seeds "
                    "on a jittered hexagonal lattice, extruded along the column axis; a particle "
                    "belongs to the column of the seed nearest its centre in the plane.");
  prm.declare_entry("column axis", "z", Selection("x|y|z"), "Axis of the columns.");
  prm.declare_entry("column diameter", "0", Double(0),
                    "Mean column diameter D (m): each seed owns on average the area pi D^2 / 4. "
                    "At least two particle diameters, at most the specimen's width.");
  prm.declare_entry("column jitter", "0.5", Double(0, 1),
                    "Seed offsets, uniform in a disc of this fraction of the lattice spacing: 0 "
                    "gives identical hexagonal columns; the coefficient of variation of the "
                    "column diameters is about 0.065 at 0.3, 0.11 at 0.5, 0.19 at 1.");
  prm.declare_entry("seed", "1", Integer(0), "Seed of the seed offsets and c-axes.");
  prm.declare_entry("c-axis", "random", Selection("random|aligned"),
                    "c-axes of the columns, in the plane across them: at a uniform random angle, "
                    "or aligned with 'c-axis direction' within 'c-axis spread'.");
  prm.declare_entry("c-axis direction", "1, 0, 0", vector3,
                    "Aligned c-axes: this direction projected into the plane across the columns.");
  prm.declare_entry("c-axis spread", "0", Double(0, 180),
                    "Aligned c-axes: standard deviation of their angle (degrees).");
  prm.declare_entry("granular layer thickness", "0", Double(0),
                    "A top layer of granular ice (m; at the upper end of the column axis) with "
                    "equiaxed grains instead of columns; 0: none.");
  prm.declare_entry("granular grain diameter", "0", Double(0),
                    "Mean diameter of the granular layer's grains (m, equivalent sphere).");
  prm.declare_entry("basal cone angle", "0", Double(0, 90),
                    "Half-angle (degrees) of a cone about each grain's c-axis: a bond inside a "
                    "grain whose axis lies within it crosses the grain's basal planes nearly "
                    "normally and is a basal bond (section Bond class basal); 0: none. Needs "
                    "grains.");
  prm.declare_entry("weak plane normal", "1, 0, 0", vector3, "Normal of the weak planes.");
  prm.declare_entry("weak plane offsets", "", List(Double(), 0),
                    "Weak planes normal . x = offset (m, the normal made unit); empty: none. A "
                    "bond whose axis crosses one is a weak_plane bond.");
  prm.declare_entry("weak plane spacing", "0", Double(0),
                    "Repeats each weak plane every spacing (m) along the normal (a parallel "
                    "set); 0: each plane once.");
  prm.leave_subsection();
  for (const char* section : class_sections)
  {
    prm.enter_subsection(section);
    prm.declare_entry("model", "", Anything(),
                      "Bond model of the class's bonds (as Bonds/model); empty: the Bonds value.");
    for (const char* key : {"youngs modulus", "poisson ratio", "radius multiplier",
                            "stiffness ratio", "normal stiffness per area"})
      prm.declare_entry(key, "", Anything(),
                        std::string("As Bonds/") + key +
                            ", for this class; empty: the Bonds value.");
    for (const char* key : {"tensile strength", "shear strength", "cohesion"})
      prm.declare_entry(key, "", Anything(),
                        std::string("As Damage/") + key +
                            ", for this class (mean; the scatter is Damage's); empty: the Damage "
                            "value.");
    for (const char* key :
         {"friction angle", "moment factor", "fracture energy mode I", "fracture energy mode II"})
      prm.declare_entry(key, "", Anything(),
                        std::string("As Damage/") + key +
                            ", for this class's bonds; empty: the Damage value. The failure "
                            "mode and the shear criterion are the specimen's (Damage).");
    if (std::string(section) == "Bond class basal")
      prm.declare_entry(
          "smooth joint", "false", Bool(),
          "true: each basal bond is a smooth joint whose normal is its grain's c-axis: it splits "
          "its force into normal and shear against the basal plane, not its own axis, fails on "
          "those and carries no couple, so its shear is the slip along the basal plane whatever "
          "the bond's axis. false: the bonds follow the bond law along their own axes.");
    if (std::string(section) == "Bond class weak_plane")
      prm.declare_entry(
          "smooth joint", "false", Bool(),
          "true: each weak-plane bond is a smooth joint (PFC's smooth-joint model, YADE's "
          "JCFpm): it splits its force into normal and shear against the plane's normal, not "
          "its own axis, and fails on those (tensile strength against the normal stress, shear "
          "strength or cohesion against the shear stress), carrying no couple; so the plane's "
          "stiffness and strength do not depend on how particles sit across it. false: the "
          "bonds follow the bond law along their own axes, as the other classes.");
    if (std::string(section) == "Bond class grain_boundary")
      prm.declare_entry(
          "joint friction", "", Anything(),
          "Empty: a pair of particles in two grains whose bond is broken, or that has none, "
          "meets as two spheres. A value mu_gb (dimensionless, >= 0): it meets as an unbonded "
          "smooth joint on the grains' boundary, the plane bisecting their two seeds (the "
          "contact law's normal force on the approach along the boundary's normal, compression "
          "only, and a shear spring in the plane capped at mu_gb times that force), so broken "
          "boundaries slide on their plane and never ride up over one another as spheres "
          "would. Not in a run over several ranks.");
    if (std::string(section) == "Bond class weak_plane")
      prm.declare_entry(
          "joint friction", "", Anything(),
          "With smooth joint: the Coulomb friction coefficient mu_j (dimensionless, >= 0) of the "
          "plane once its bonds break; empty: 0.5. Only smooth joints slide on the plane, so a "
          "value set while smooth joint is false is refused. A pair of particles on the plane's "
          "two sides whose bond "
          "is broken, or that has none, meets as an unbonded smooth joint (PFC's, YADE JCFpm's): "
          "the contact law's normal force on the approach along the plane's normal, compression "
          "only, and a shear spring in the plane capped at mu_j times that force, so the two "
          "sides slide on the plane and never ride up over one another as spheres would.");
    prm.leave_subsection();
  }
}

namespace
{
/// The Microstructure section itself: the columns and the weak planes.
void parse_grains_and_planes(ParameterHandler& prm, dem::MicrostructureConfig& c)
{
  prm.enter_subsection("Microstructure");
  auto& g = c.grains;
  g.enabled = prm.get("grains") == "columnar";
  g.axis = prm.get("column axis")[0] - 'x';
  g.diameter = prm.get_double("column diameter");
  g.jitter = prm.get_double("column jitter");
  g.seed = static_cast<unsigned long>(prm.get_integer("seed"));
  g.c_axis_aligned = prm.get("c-axis") == "aligned";
  g.c_axis_direction = get_vec3(prm, "c-axis direction");
  g.c_axis_spread = prm.get_double("c-axis spread");
  g.granular_thickness = prm.get_double("granular layer thickness");
  g.granular_diameter = prm.get_double("granular grain diameter");
  c.basal_cone = prm.get_double("basal cone angle");
  if (c.basal_cone > 0 && !g.enabled)
    throw dem::InputError("Microstructure/basal cone angle: set, but the case has no grains "
                          "(Microstructure/grains = columnar gives them their c-axes)");
  const auto offsets =
      dem::parse_numbers(prm.get("weak plane offsets"), "Microstructure/weak plane offsets");
  const double spacing = prm.get_double("weak plane spacing");
  if (!offsets.empty())
    c.weak_planes = dem::WeakPlaneSet{get_vec3(prm, "weak plane normal"), offsets, spacing};
  else if (spacing > 0)
    throw dem::InputError("Microstructure/weak plane spacing: a spacing without 'weak plane "
                          "offsets' gives no plane (set at least one offset)");
  prm.leave_subsection();
  g.validate();
}
} // namespace

dem::MicrostructureConfig parse_microstructure_parameters(ParameterHandler& prm,
                                                          const dem::BondMaterial& material,
                                                          const dem::DamageConfig& damage)
{
  dem::MicrostructureConfig c;
  parse_grains_and_planes(prm, c);
  const auto& g = c.grains;

  const bool has_class[] = {g.enabled, c.weak_planes.has_value(), c.basal_cone > 0};
  const char* const needs[] = {"Microstructure/grains = columnar",
                               "Microstructure/weak plane offsets",
                               "Microstructure/basal cone angle"};
  const char* const class_bonds[] = {"grain-boundary", "weak-plane", "basal"};
  for (int k = 0; k < 3; ++k)
  {
    const std::string section = class_sections[k];
    prm.enter_subsection(section);
    dem::BondClassConfig cls = dem::BondClassConfig::of_specimen(material, damage);
    bool set = false;
    std::string first_set;
    auto value = [&](const char* key, double fallback)
    {
      const bool before = set;
      const double v = number_or(prm, section, key, fallback, set);
      if (set && !before)
        first_set = key;
      return v;
    };
    if (const std::string model = prm.get("model");
        model.find_first_not_of(" \t") != std::string::npos)
    {
      try
      {
        cls.material.model = dem::bond_model_from_name(model);
      }
      catch (const dem::InputError& e)
      {
        throw dem::InputError(section + "/model: " + e.what());
      }
      set = true, first_set = "model";
    }
    auto& m = cls.material;
    m.youngs_modulus = value("youngs modulus", m.youngs_modulus);
    m.poisson_ratio = value("poisson ratio", m.poisson_ratio);
    m.radius_multiplier = value("radius multiplier", m.radius_multiplier);
    m.stiffness_ratio = value("stiffness ratio", m.stiffness_ratio);
    m.normal_stiffness_per_area = value("normal stiffness per area", m.normal_stiffness_per_area);
    cls.tensile_strength = value("tensile strength", cls.tensile_strength);
    cls.shear_strength = value("shear strength", cls.shear_strength);
    cls.cohesion = value("cohesion", cls.cohesion);
    cls.friction_angle = value("friction angle", cls.friction_angle);
    cls.moment_factor = value("moment factor", cls.moment_factor);
    cls.fracture_energy_I = value("fracture energy mode I", cls.fracture_energy_I);
    cls.fracture_energy_II = value("fracture energy mode II", cls.fracture_energy_II);
    const bool smooth = k > 0 && prm.get_bool("smooth joint");
    if (k == 1)
      c.joint_friction = joint_friction(prm, section, smooth, c.joint_friction);
    if (k == 0 && !blank(prm.get("joint friction")))
    {
      c.boundary_joint_friction = joint_friction(prm, section, true, 0.0);
      if (!has_class[0])
        throw dem::InputError(section + "/joint friction: set, but the case has no grains "
                                        "(Microstructure/grains = columnar makes them)");
    }
    prm.leave_subsection();
    if (smooth && !has_class[k])
      throw dem::InputError(section + "/smooth joint: true, but the case has no " + class_bonds[k] +
                            " bonds (" + needs[k] + " makes them)");
    if (smooth)
      (k == 1 ? c.smooth_joint : c.basal_smooth_joint) = true;
    if (set && !has_class[k])
      throw dem::InputError(section + "/" + first_set + ": set, but the case has no such bonds (" +
                            needs[k] + " makes them)");
    if (set)
      (k == 0 ? c.grain_boundary : k == 1 ? c.weak_plane : c.basal) = cls;
  }
  return c;
}
} // namespace dembridge::app
