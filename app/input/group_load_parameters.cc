#include "app/input/group_load_parameters.h"
#include "app/input/parameter_values.h"

namespace dembridge::app
{
using dealii::ParameterHandler;
using dealii::Patterns::Anything;
using dealii::Patterns::Double;
using dealii::Patterns::Integer;
using dealii::Patterns::List;
using dealii::Patterns::Selection;
namespace dem = dembridge::dem;

void declare_group_parameters(ParameterHandler& prm, const std::vector<std::string>& names)
{
  for (const auto& name : names)
  {
    prm.enter_subsection("Group " + name);
    prm.declare_entry("select", "index", Selection("all|index|box|face|nearest"),
                      "How the group is selected.");
    prm.declare_entry("point", "0, 0, 0", vector3,
                      "select = nearest: the one particle whose centre is nearest this point (m).");
    prm.declare_entry("indices", "", List(Integer(), 0),
                      "Particle indices (select = index); negative counts from the end.");
    prm.declare_entry("box min", "0, 0, 0", vector3, "Lower corner (m), select = box.");
    prm.declare_entry("box max", "0, 0, 0", vector3, "Upper corner (m), select = box.");
    prm.declare_entry("face", "x-", Selection("x-|x+|y-|y+|z-|z+"),
                      "Specimen face, select = face.");
    prm.declare_entry("face thickness", "1.5", Double(0),
                      "Centres within thickness x radius of the face (thesis: 1.5).");
    prm.declare_entry("fixed", "", Anything(), "Held DOFs: any of ux, uy, uz, rx, ry, rz, or all.");
    prm.declare_entry("mass", "0", Double(0), "Mass of each particle (kg); 0: density x volume.");
    prm.declare_entry("initial velocity", "0, 0, 0", vector3, "Initial velocity (m/s).");
    prm.leave_subsection();
  }
}

void declare_load_parameters(ParameterHandler& prm, const std::vector<std::string>& names)
{
  for (const auto& name : names)
  {
    prm.enter_subsection("Load " + name);
    prm.declare_entry("group", "", Anything(), "Group the load acts on.");
    prm.declare_entry("type", "force",
                      Selection("force|moment|velocity|angular velocity|displacement|pressure"),
                      "force/moment: group total (N, N·m) shared equally; velocity/angular "
                      "velocity: prescribed per particle (m/s, rad/s), explicit solver only; "
                      "displacement: prescribed per particle (m), reached at the end of the ramp "
                      "and held, read the same by the static and explicit solvers; pressure: a "
                      "normal stress on a face group, (pressure x ramp + ratio x the stress of "
                      "the ratio load) x area along value (the direction it pushes), shared "
                      "equally: a confining stress, held or in proportion to the axial one.");
    prm.declare_entry("ramp profile", "linear", Selection("linear|smooth"),
                      "Displacement loads: linear (constant velocity over the ramp) or smooth "
                      "(3 s^2 - 2 s^3: zero velocity at both ends).");
    prm.declare_entry("value", "0, 0, 0", vector3, "Full value, reached at the end of the ramp.");
    prm.declare_entry("components", "x, y, z", List(Selection("x|y|z"), 1, 3),
                      "Prescribed components (velocity and displacement types).");
    prm.declare_entry("ramp time", "0", Double(0), "Linear ramp from 0 over this time (s).");
    prm.declare_entry("pressure", "0", Double(),
                      "Pressure loads: the confining stress p_0 (Pa), ramped as a force.");
    prm.declare_entry("ratio", "0", Double(),
                      "Pressure loads: R, the share of the ratio load's stress added to p_0 "
                      "(sigma_2 = p_0 + R sigma_1), followed step by step.");
    prm.declare_entry("ratio load", "", Anything(),
                      "Pressure loads with a ratio: the displacement or velocity load whose "
                      "support reaction along its value, over its area, is sigma_1.");
    prm.declare_entry("area", "0", Double(0),
                      "Face area (m^2): a pressure's, or that of a load a pressure follows.");
    prm.declare_entry("end time", "inf", Anything(),
                      "Time (s) at which the load is removed / the DOFs released; 'inf': never.");
    prm.leave_subsection();
  }
}

std::vector<dem::GroupConfig> parse_group_sections(ParameterHandler& prm)
{
  std::vector<dem::GroupConfig> groups;
  for (const auto& name : listed_names(prm, "Groups"))
  {
    dem::GroupConfig g;
    g.name = name;
    const std::string where = "Group " + name;
    prm.enter_subsection(where);
    using GK = dem::GroupSelection::Kind;
    const std::string sel = prm.get("select");
    g.selection.kind = sel == "all"     ? GK::all
                       : sel == "index" ? GK::index
                       : sel == "box"   ? GK::box
                       : sel == "face"  ? GK::face
                                        : GK::nearest;
    for (const auto& s : dealii::Utilities::split_string_list(prm.get("indices"), ','))
      g.selection.indices.push_back(std::stol(s));
    if (g.selection.kind == GK::index && g.selection.indices.empty())
      throw dem::InputError(where + "/indices: select = index needs at least one index");
    g.selection.box_min = get_vec3(prm, "box min");
    g.selection.box_max = get_vec3(prm, "box max");
    std::tie(g.selection.face_axis, g.selection.face_upper) =
        dem::parse_face(prm.get("face"), where + "/face");
    g.selection.face_thickness = prm.get_double("face thickness");
    g.selection.point = get_vec3(prm, "point");
    g.fixed = dem::parse_dof_mask(prm.get("fixed"), where + "/fixed");
    g.mass = prm.get_double("mass");
    g.initial_velocity = get_vec3(prm, "initial velocity");
    prm.leave_subsection();
    groups.push_back(g);
  }
  return groups;
}

std::vector<dem::LoadConfig> parse_load_sections(ParameterHandler& prm)
{
  std::vector<dem::LoadConfig> loads;
  for (const auto& name : listed_names(prm, "Loads"))
  {
    dem::LoadConfig lc;
    const std::string where = "Load " + name;
    prm.enter_subsection(where);
    lc.load.name = name;
    lc.group = prm.get("group");
    if (lc.group.empty())
      throw dem::InputError(where + "/group: a load needs a group");
    const std::string type = prm.get("type");
    lc.load.kind = type == "force"          ? dem::LoadKind::force
                   : type == "moment"       ? dem::LoadKind::moment
                   : type == "velocity"     ? dem::LoadKind::velocity
                   : type == "displacement" ? dem::LoadKind::displacement
                   : type == "pressure"     ? dem::LoadKind::pressure
                                            : dem::LoadKind::angular_velocity;
    lc.load.pressure = prm.get_double("pressure");
    lc.load.ratio = prm.get_double("ratio");
    lc.load.area = prm.get_double("area");
    lc.ratio_load = prm.get("ratio load");
    lc.load.profile =
        prm.get("ramp profile") == "smooth" ? dem::RampProfile::smooth : dem::RampProfile::linear;
    lc.load.value = get_vec3(prm, "value");
    lc.load.components = 0;
    for (const auto& comp : dealii::Utilities::split_string_list(prm.get("components"), ','))
      lc.load.components |= std::uint8_t(1u << (comp[0] - 'x'));
    lc.load.ramp_time = prm.get_double("ramp time");
    lc.load.end_time = get_end_time(prm, where);
    prm.leave_subsection();
    loads.push_back(lc);
  }
  return loads;
}
} // namespace dembridge::app
