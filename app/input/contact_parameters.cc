#include "app/input/contact_parameters.h"
#include "app/input/dem_parameters.h"
#include "app/input/parameter_values.h"
#include <algorithm>

namespace dembridge::app
{
using dealii::ParameterHandler;
using dealii::Patterns::Anything;
using dealii::Patterns::Bool;
using dealii::Patterns::Double;
using dealii::Patterns::Selection;
namespace dem = dembridge::dem;

void declare_contact_parameters(ParameterHandler& prm)
{
  prm.enter_subsection("Contacts");
  prm.declare_entry(
      "model", "none", Selection(dem::contact_model_selection()),
      "Contact law between particles that touch without an intact bond (never bonded, or "
      "broken) and between particles and walls: none; linear (spring-dashpot with Coulomb "
      "friction, thesis eq. 12-13); hertz_mindlin (Hertz normal, Mindlin tangential, Tsuji "
      "damping, as EDEM).");
  prm.declare_entry("youngs modulus", "0", Double(),
                    "Young's modulus E of the particles (Pa), hertz_mindlin; walls are rigid.");
  prm.declare_entry("poisson ratio", "0.25", Double(),
                    "Poisson's ratio nu of the particles, in (-1, 0.5), hertz_mindlin.");
  prm.declare_entry("normal stiffness", "0", Double(),
                    "Normal contact stiffness k_n (N/m), linear.");
  prm.declare_entry("tangential stiffness", "0", Double(),
                    "Tangential contact stiffness k_t (N/m), linear; 0: 2/7 k_n.");
  prm.declare_entry("restitution coefficient", "1", Double(),
                    "Coefficient of restitution e in (0, 1]; sets the contact dashpots.");
  prm.declare_entry("friction coefficient", "0.5", Double(),
                    "Coulomb friction coefficient mu >= 0 (particles and walls).");
  prm.declare_entry("rolling friction", "0", Double(),
                    "Rolling friction coefficient mu_r >= 0 (Ai et al. 2011, elastic-plastic "
                    "rolling spring: |M_r| <= mu_r R* F_n); 0: no rolling resistance.");
  prm.declare_entry("rolling stiffness", "0", Double(),
                    "Rolling stiffness k_r (N·m/rad); 0: 2.25 k_n mu_r^2 R*^2 (Ai et al.).");
  prm.declare_entry("skin", "0", Double(),
                    "Verlet skin of the neighbour search (m): the list is rebuilt once a "
                    "particle has moved half of it; 0: a fifth of the smallest radius.");
  prm.declare_entry("monitor", "false", Bool(),
                    "Measure the first contact: contact_duration, max_overlap, max_contact_force "
                    "and restitution_coefficient in summary.json.");
  prm.declare_entry("platens", "", Anything(),
                    "'lower, upper': two walls facing each other that load the specimen; their "
                    "mean force over the specimen's cross-section and their approach over their "
                    "initial distance give peak_stress and strain_at_peak (compression "
                    "positive).");
  prm.declare_entry("reference tensile strength", "0", Double(),
                    "Peak stress (Pa) of a tension test of the same specimen and "
                    "micro-parameters (its summary's peak_stress); with platens, summary.json "
                    "reports compressive_to_tensile_strength_ratio = peak_stress / this "
                    "(PFC's parallel bonds: about 7, granite: about 20). 0: none.");
  prm.leave_subsection();

  prm.enter_subsection("Walls");
  prm.declare_entry("names", "", Anything(),
                    "Comma-separated wall names; each needs a 'subsection Wall NAME'.");
  prm.leave_subsection();
}

void declare_wall_parameters(ParameterHandler& prm, const std::vector<std::string>& names)
{
  for (const auto& name : names)
  {
    prm.enter_subsection("Wall " + name);
    prm.declare_entry("point", "0, 0, 0", vector3, "A point of the plane at t = 0 (m).");
    prm.declare_entry("normal", "0, 0, 1", vector3,
                      "Normal of the plane, pointing to the particles' side.");
    prm.declare_entry("velocity", "0, 0, 0", vector3,
                      "Velocity of the wall (m/s), reached at the end of the ramp.");
    prm.declare_entry("ramp time", "0", Double(),
                      "The velocity ramps linearly from 0 over this time (s).");
    prm.declare_entry("end time", "inf", Anything(),
                      "Time (s) at which the wall stops; 'inf': never.");
    prm.declare_entry("touch", "false", Bool(),
                      "true: at t = 0 the plane is moved along its normal until it touches the "
                      "outermost particle on its side (a platen laid on a specimen whose extent "
                      "the case does not know).");
    prm.leave_subsection();
  }
}

void parse_contact_parameters(ParameterHandler& prm, dem::CaseConfig& c)
{
  auto& k = c.contacts;
  prm.enter_subsection("Contacts");
  k.model = dem::contact_model_from_name(prm.get("model"));
  k.youngs_modulus = prm.get_double("youngs modulus");
  k.poisson_ratio = prm.get_double("poisson ratio");
  k.normal_stiffness = prm.get_double("normal stiffness");
  k.tangential_stiffness = prm.get_double("tangential stiffness");
  k.restitution = prm.get_double("restitution coefficient");
  k.friction = prm.get_double("friction coefficient");
  k.rolling_friction = prm.get_double("rolling friction");
  k.rolling_stiffness = prm.get_double("rolling stiffness");
  k.skin = prm.get_double("skin");
  k.monitor = prm.get_bool("monitor");
  k.platens = split_names(prm.get("platens"));
  k.reference_tensile_strength = prm.get_double("reference tensile strength");
  prm.leave_subsection();
  k.validate();

  for (const auto& name : listed_names(prm, "Walls"))
  {
    dem::WallConfig w;
    w.name = name;
    const std::string where = "Wall " + name;
    prm.enter_subsection(where);
    w.point = get_vec3(prm, "point");
    w.normal = get_vec3(prm, "normal");
    w.velocity = get_vec3(prm, "velocity");
    w.ramp_time = prm.get_double("ramp time");
    w.touch = prm.get_bool("touch");
    w.end_time = get_end_time(prm, where);
    prm.leave_subsection();
    w.validate();
    for (const auto& other : c.walls)
      if (other.name == name)
        throw dem::InputError("Walls/names: wall '" + name + "' is named twice");
    c.walls.push_back(w);
  }
  if (!c.walls.empty() && !k.enabled())
    throw dem::InputError("Contacts/model: walls act through contacts; choose linear or "
                          "hertz_mindlin");
  if (!k.platens.empty())
  {
    std::string listed;
    for (const auto& w : c.walls)
      listed += (listed.empty() ? "" : ", ") + w.name;
    listed =
        listed.empty() ? "the case has no wall: Walls/names is empty" : "Walls/names = " + listed;
    if (k.platens.size() != 2)
      throw dem::InputError("Contacts/platens: expected the names of two walls 'lower, upper', "
                            "got " +
                            std::to_string(k.platens.size()) + " (" + listed + ")");
    for (const auto& name : k.platens)
      if (std::none_of(c.walls.begin(), c.walls.end(),
                       [&](const dem::WallConfig& w) { return w.name == name; }))
        throw dem::InputError("Contacts/platens: '" + name + "' is not a wall (" + listed + ")");
    if (k.platens[0] == k.platens[1])
      throw dem::InputError("Contacts/platens: '" + k.platens[0] +
                            "' is named twice; the platens are two walls facing each other");
  }
}
} // namespace dembridge::app
