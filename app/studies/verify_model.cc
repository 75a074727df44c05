// dembridge verify: the FE model of a DEM specimen test (see verify_model.h).
//
// How the FE problem is derived from the DEM case (docs/fem.md, "FEM vs DEM"):
//  * uniaxial test (Measurements/modulus groups = fixed, loaded; axis a): the FE body spans the
//    specimen's extent across a and, along a, the distance between the two end groups' centroids
//    (where the DEM holds and moves its end particles; their outer halves move rigidly with the
//    grips). The fixed end face holds the translations its group holds; the loaded end face gets
//    the DEM's load: a prescribed displacement (the DEM's measured end displacement; for the
//    static solver exactly the prescribed value) or the total force. Lateral rigid-body motion
//    that neither end removes is removed on the lateral min faces (symmetry planes, exact for a
//    homogeneous state).
//  * three-point bending (Measurements/flexural groups = pin, roller, loaded, bottom; span x,
//    load z as in the DEM measurement): the FE body is the specimen's extent; the supports are
//    bottom-face strips under the pin and roller particles (their x extent, radii included) held
//    in the translations the groups hold; the load is the DEM force, spread over the top-face
//    strip above the loaded particles; the deflections are FE displacements at the centres of the
//    loaded and bottom particles, as the DEM measures them.
#include "app/studies/verify_model.h"
#include "dem/model/groups.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace dembridge::app::verify_detail
{
using nlohmann::json;

namespace
{
const char* const axis_name = "xyz";

std::string vec(const dem::Vec3& v)
{
  return num(v.x()) + "," + num(v.y()) + "," + num(v.z());
}
std::string components(std::uint8_t mask)
{
  std::string c;
  for (int d = 0; d < 3; ++d)
    if (mask & (1u << d))
      c += axis_name[d];
  return c;
}

const dem::GroupConfig& group_config(const dem::CaseConfig& c, const std::string& name,
                                     const std::string& where)
{
  for (const auto& g : c.groups)
    if (g.name == name)
      return g;
  throw std::runtime_error(where + ": no group named '" + name + "'");
}

/// The loads acting on @p group; any load on another group is refused (the FE model would miss
/// it). Prescribed rotations have no continuum counterpart.
std::vector<dem::LoadConfig> loads_on(const dem::CaseConfig& c, const std::string& group)
{
  std::vector<dem::LoadConfig> out;
  for (const auto& l : c.loads)
  {
    if (l.group != group)
      throw std::runtime_error("Load " + l.load.name + "/group: verify maps only a load on '" +
                               group + "' to the FE model, not one on '" + l.group + "'");
    if (l.load.kind == dem::LoadKind::moment || l.load.kind == dem::LoadKind::angular_velocity)
      throw std::runtime_error("Load " + l.load.name +
                               "/type: moments and rotations have no FE counterpart");
    if (l.load.kind == dem::LoadKind::pressure)
      throw std::runtime_error("Load " + l.load.name +
                               "/type: verify maps no pressure to the FE model");
    out.push_back(l);
  }
  return out;
}

} // namespace

std::string num(double v)
{
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

Plan make_plan(const dem::CaseConfig& c, const dem::Model& model, const std::string& test)
{
  Plan p;
  std::tie(p.lo, p.hi) = dem::reference_extent(model.particles);
  p.body_lo = p.lo, p.body_hi = p.hi;
  p.n_particles = model.particles.size();
  for (double r : model.particles.radius)
    p.mean_diameter += 2 * r / double(model.particles.size());
  const auto& m = c.measure;
  const bool uniaxial = !m.modulus_fixed_group.empty(), bending = !m.flexural_groups.empty();
  p.test = test;
  if (test == "auto")
  {
    if (uniaxial == bending)
      throw std::runtime_error(
          uniaxial ? "Verification/test: the case measures both a uniaxial and a bending test; "
                     "choose one"
                   : "Measurements: verify needs 'modulus groups' (uniaxial test) or 'flexural "
                     "groups' (three-point bending); the case sets neither");
    p.test = uniaxial ? "uniaxial" : "bending";
  }
  if (p.test == "uniaxial" && !uniaxial)
    throw std::runtime_error("Measurements/modulus groups: not set (Verification/test = uniaxial)");
  if (p.test == "bending" && !bending)
    throw std::runtime_error("Measurements/flexural groups: not set (Verification/test = bending)");

  auto members = [&](const std::string& name, const std::string& where) -> const dem::Group&
  { return model.groups[model.group_index(name, where)]; };
  auto centroid = [&](const dem::Group& g)
  {
    dem::Vec3 x = dem::Vec3::Zero();
    for (int i : g.members)
      x += model.particles.reference_position[i] / double(g.members.size());
    return x;
  };
  std::vector<std::string>& mapped = p.mapped_groups;
  if (p.test == "uniaxial")
  {
    const std::string where = "Measurements/modulus groups";
    p.axis = m.modulus_axis;
    p.fixed_group = m.modulus_fixed_group, p.loaded_group = m.modulus_loaded_group;
    const int a = p.axis;
    const double xf = centroid(members(p.fixed_group, where))[a];
    const double xl = centroid(members(p.loaded_group, where))[a];
    p.body_lo[a] = std::min(xf, xl), p.body_hi[a] = std::max(xf, xl);
    p.fixed_face = std::string(1, axis_name[a]) + (xf < xl ? "-min" : "-max");
    p.loaded_face = std::string(1, axis_name[a]) + (xf < xl ? "-max" : "-min");
    const auto& fixed = group_config(c, p.fixed_group, where);
    p.fixed_components = components(fixed.fixed);
    if (p.fixed_components.find(axis_name[a]) == std::string::npos)
      throw std::runtime_error("Group " + p.fixed_group +
                               "/fixed: the fixed end of the uniaxial "
                               "test must hold u" +
                               std::string(1, axis_name[a]));
    p.loaded_held_components = components(group_config(c, p.loaded_group, where).fixed);
    const auto loads = loads_on(c, p.loaded_group);
    if (loads.empty())
      throw std::runtime_error("Loads: no load acts on the loaded end group '" + p.loaded_group +
                               "'");
    for (const auto& l : loads)
      if (l.load.kind == dem::LoadKind::velocity || l.load.kind == dem::LoadKind::displacement)
      {
        p.displacement_control = true;
        p.load_components += components(l.load.components);
      }
      else
        p.load_force += l.load.value;
    if (p.displacement_control && p.load_force.norm() > 0)
      throw std::runtime_error("Load " + loads[0].load.name +
                               "/type: the loaded end has both a "
                               "prescribed motion and a force");
    if (p.displacement_control && p.load_components.find(axis_name[a]) == std::string::npos)
      throw std::runtime_error("Load " + loads[0].load.name +
                               "/components: the loaded end must "
                               "be moved along " +
                               std::string(1, axis_name[a]));
    mapped = {p.fixed_group, p.loaded_group};
  }
  else
  {
    const std::string where = "Measurements/flexural groups";
    p.axis = 0; // span x, load z (dem::flexural_response)
    p.pin = m.flexural_groups[0], p.roller = m.flexural_groups[1];
    p.loaded = m.flexural_groups[2], p.bottom = m.flexural_groups[3];
    auto strip = [&](const std::string& name, double z)
    {
      const auto& g = members(name, where);
      double x0 = p.hi.x(), x1 = p.lo.x();
      for (int i : g.members)
      {
        const double x = model.particles.reference_position[i].x(), r = model.particles.radius[i];
        x0 = std::min(x0, x - r), x1 = std::max(x1, x + r);
      }
      return name + ": " + num(x0) + "," + num(p.lo.y()) + "," + num(z) + " to " + num(x1) + "," +
             num(p.hi.y()) + "," + num(z);
    };
    p.patches = strip(p.pin, p.lo.z()) + "; " + strip(p.roller, p.lo.z()) + "; " +
                strip(p.loaded, p.hi.z());
    p.pin_components = components(group_config(c, p.pin, where).fixed);
    p.roller_components = components(group_config(c, p.roller, where).fixed);
    for (const auto& [name, comps] :
         {std::pair{p.pin, p.pin_components}, {p.roller, p.roller_components}})
      if (comps.find('z') == std::string::npos)
        throw std::runtime_error("Group " + name +
                                 "/fixed: a support of the bending test must "
                                 "hold uz");
    const auto loads = loads_on(c, p.loaded);
    if (loads.empty())
      throw std::runtime_error("Loads: no load acts on the loaded group '" + p.loaded + "'");
    for (const auto& l : loads)
    {
      if (l.load.kind != dem::LoadKind::force)
        throw std::runtime_error("Load " + l.load.name + "/type: the bending load must be a force");
      p.load_force += l.load.value;
    }
    auto points = [&](const std::string& name)
    {
      std::string text;
      for (int i : members(name, where).members)
        text += (text.empty() ? "" : "; ") + vec(model.particles.reference_position[i]);
      return text;
    };
    p.top_points = points(p.loaded), p.bottom_points = points(p.bottom);
    mapped = {p.pin, p.roller, p.loaded, p.bottom};
  }
  for (const auto& g : c.groups)
    if (g.fixed != 0 && std::find(mapped.begin(), mapped.end(), g.name) == mapped.end())
      p.ignored_groups.push_back(g.name);
  return p;
}

Layers layers_from(const json& dem, const Plan& p, int n, int axis)
{
  Layers l;
  if (dem.contains("stress_layers"))
  {
    const auto& s = dem["stress_layers"];
    const std::string a = s.value("axis", "z");
    l.axis = a.empty() ? 2 : a[0] - 'x';
    l.edges = s.at("edges").get<std::vector<double>>();
    if (l.axis < 0 || l.axis > 2 || l.edges.size() < 2)
      throw std::runtime_error("DEM summary: stress_layers has a bad axis or fewer than two edges");
    return l;
  }
  l.axis = axis;
  for (int k = 0; k <= n; ++k)
    l.edges.push_back(p.lo[axis] + (p.hi[axis] - p.lo[axis]) * k / n);
  return l;
}

std::string fe_case(const Plan& p, const ElasticConstants& mat, const json& dem, int degree,
                    double cell_size, const Layers& layers)
{
  std::array<unsigned, 3> n{};
  for (int d = 0; d < 3; ++d)
    n[d] = std::max(1u, unsigned(std::lround((p.body_hi[d] - p.body_lo[d]) / cell_size)));
  // Layer edges on cell faces where the body spans the slabs: a multiple of the slab count.
  const int la = layers.axis;
  const unsigned n_layers = unsigned(layers.edges.size() - 1);
  if (std::abs(p.body_lo[la] - layers.edges.front()) < 1e-9 * (p.hi - p.lo).norm() &&
      std::abs(p.body_hi[la] - layers.edges.back()) < 1e-9 * (p.hi - p.lo).norm())
    n[la] = n_layers * std::max(1u, unsigned(std::lround(double(n[la]) / n_layers)));

  std::ostringstream s;
  s << "# Derived by `dembridge verify` from the DEM case; runnable with `dembridge run`.\n"
    << "set Mode = fem\nsubsection FEM\n  set problem = static\n  set degree = " << degree
    << "\n  subsection Mesh\n    set source = box\n    set box lower = " << vec(p.body_lo)
    << "\n    set box upper = " << vec(p.body_hi) << "\n    set box subdivisions = " << n[0] << ","
    << n[1] << "," << n[2] << "\n";
  if (!p.patches.empty())
    s << "    set patches = " << p.patches << "\n";
  s << "  end\n  subsection Material\n";
  if (mat.stiffness_tensor)
  {
    s << "    set model = anisotropic\n    set voigt stiffness = ";
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        s << (i + j ? ", " : "") << num((*mat.stiffness_tensor)(i, j));
    s << "\n";
  }
  else if (mat.shear_modulus > 0)
  {
    // cubic: compliance S11 = 1/E, S12 = -nu/E, S44 = 1/G; the normal block inverts as for the
    // isotropic material, the shear block is G.
    const double E = mat.youngs_modulus, nu = mat.poisson_ratio;
    const double c11 = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)),
                 c12 = E * nu / ((1 + nu) * (1 - 2 * nu));
    s << "    set model = anisotropic\n    set voigt stiffness = ";
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
      {
        const double c = i < 3 && j < 3 ? (i == j ? c11 : c12) : (i == j ? mat.shear_modulus : 0.0);
        s << (i + j ? ", " : "") << num(c);
      }
    s << "\n";
  }
  else
    s << "    set model = isotropic\n    set youngs modulus = " << num(mat.youngs_modulus)
      << "\n    set poisson ratio = " << num(mat.poisson_ratio) << "\n";
  s << "  end\n";
  std::string boundaries, forces, measurements;
  if (p.test == "uniaxial")
  {
    const int a = p.axis;
    const auto& groups = dem.at("groups");
    auto mean_u = [&](const std::string& g, int d)
    { return groups.at(g).at("mean_displacement").at(d).get<double>(); };
    std::string held_somewhere = p.fixed_components + p.loaded_held_components;
    boundaries = p.fixed_face + ": " + p.fixed_components;
    if (!p.loaded_held_components.empty())
      boundaries += "; " + p.loaded_face + ": " + p.loaded_held_components;
    if (p.displacement_control)
      for (const char c : p.load_components)
      {
        const int d = c - 'x';
        // relative to the fixed end along the axis (the FE fixed face does not move)
        const double u = mean_u(p.loaded_group, d) - (d == a ? mean_u(p.fixed_group, a) : 0.0);
        boundaries += "; " + p.loaded_face + ": " + std::string(1, c) + " = " + num(u);
        held_somewhere += c;
      }
    else
      forces = p.loaded_face + ": " + vec(p.load_force);
    for (int d = 0; d < 3; ++d)
      if (d != a && held_somewhere.find(axis_name[d]) == std::string::npos)
        boundaries += "; " + std::string(1, axis_name[d]) + "-min: " + axis_name[d];
    dem::Vec3 e = dem::Vec3::Zero();
    e[a] = 1;
    measurements = "    set reaction boundary = " + p.fixed_face +
                   "\n    set reaction direction = " + vec(e) +
                   "\n    set loaded boundary = " + p.loaded_face +
                   "\n    set reaction boundaries = " + p.fixed_face + ", " + p.loaded_face + "\n";
  }
  else
  {
    boundaries = p.pin + ": " + p.pin_components + "; " + p.roller + ": " + p.roller_components;
    forces = p.loaded + ": " + vec(p.load_force);
    measurements = "    set reaction boundaries = " + p.pin + ", " + p.roller +
                   "\n    set point groups = top: " + p.top_points +
                   " | bottom: " + p.bottom_points + "\n";
  }
  s << "  subsection Boundary conditions\n    set boundaries = " << boundaries << "\n  end\n";
  s << "  subsection Loads\n    set boundary forces = " << forces << "\n  end\n";
  s << "  subsection Measurements\n"
    << measurements << "    set stress layers = " << axis_name[la] << ":";
  for (std::size_t k = 0; k < layers.edges.size(); ++k)
    s << (k ? ", " : " ") << num(layers.edges[k]);
  s << "\n  end\n  subsection Solver\n    set tolerance = 1e-10\n  end\n"
    << "  subsection Output\n    set vtu = true\n    set base name = fem\n  end\nend\n";
  return s.str();
}
} // namespace dembridge::app::verify_detail
