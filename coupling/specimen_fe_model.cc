// The FE model of a DEM specimen test (see specimen_fe_model.h for how it is derived).
#include "coupling/specimen_fe_model.h"
#include "dem/model/groups.h"
#include "fem/parameters_text.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace dembridge::coupling
{
using nlohmann::json;

namespace
{
const char* const axis_name = "xyz";

dealii::Point<3> point(const dem::Vec3& v)
{
  return dealii::Point<3>(v.x(), v.y(), v.z());
}

fem::ComponentSet component_set(std::uint8_t mask)
{
  return {{(mask & 1u) != 0, (mask & 2u) != 0, (mask & 4u) != 0}};
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

const dem::Group& group_members(const dem::Model& model, const std::string& name,
                                const std::string& where)
{
  return model.groups[model.group_index(name, where)];
}

dem::Vec3 centroid(const dem::Model& model, const dem::Group& g)
{
  dem::Vec3 x = dem::Vec3::Zero();
  for (int i : g.members)
    x += model.particles.reference_position[i] / double(g.members.size());
  return x;
}

std::string face_name(int axis, bool max_side)
{
  return std::string(1, axis_name[axis]) + (max_side ? "-max" : "-min");
}

void read_uniaxial(SpecimenTest& t, const dem::CaseConfig& c, const dem::Model& model)
{
  const std::string where = "Measurements/modulus groups";
  const auto& m = c.measure;
  t.axis = m.modulus_axis;
  t.fixed_group = m.modulus_fixed_group, t.loaded_group = m.modulus_loaded_group;
  const int a = t.axis;
  const double xf = centroid(model, group_members(model, t.fixed_group, where))[a];
  const double xl = centroid(model, group_members(model, t.loaded_group, where))[a];
  t.body_lo[a] = std::min(xf, xl), t.body_hi[a] = std::max(xf, xl);
  t.fixed_face = face_name(a, !(xf < xl));
  t.loaded_face = face_name(a, xf < xl);
  t.fixed_components = group_config(c, t.fixed_group, where).fixed;
  if (!(t.fixed_components & (1u << a)))
    throw std::runtime_error("Group " + t.fixed_group +
                             "/fixed: the fixed end of the uniaxial test must hold u" +
                             std::string(1, axis_name[a]));
  t.loaded_held_components = group_config(c, t.loaded_group, where).fixed;
  const auto loads = loads_on(c, t.loaded_group);
  if (loads.empty())
    throw std::runtime_error("Loads: no load acts on the loaded end group '" + t.loaded_group +
                             "'");
  for (const auto& l : loads)
    if (l.load.kind == dem::LoadKind::velocity || l.load.kind == dem::LoadKind::displacement)
    {
      t.displacement_control = true;
      t.load_components |= l.load.components;
    }
    else
      t.load_force += l.load.value;
  if (t.displacement_control && t.load_force.norm() > 0)
    throw std::runtime_error("Load " + loads[0].load.name +
                             "/type: the loaded end has both a prescribed motion and a force");
  if (t.displacement_control && !(t.load_components & (1u << a)))
    throw std::runtime_error("Load " + loads[0].load.name +
                             "/components: the loaded end must be moved along " +
                             std::string(1, axis_name[a]));
  t.mapped_groups = {t.fixed_group, t.loaded_group};
}

void read_bending(SpecimenTest& t, const dem::CaseConfig& c, const dem::Model& model)
{
  const std::string where = "Measurements/flexural groups";
  const auto& groups = c.measure.flexural_groups;
  t.axis = 0; // span x, load z (dem::flexural_response)
  t.pin = groups[0], t.roller = groups[1], t.loaded = groups[2], t.bottom = groups[3];
  auto strip = [&](const std::string& name, double z)
  {
    double x0 = t.hi.x(), x1 = t.lo.x();
    for (int i : group_members(model, name, where).members)
    {
      const double x = model.particles.reference_position[i].x(), r = model.particles.radius[i];
      x0 = std::min(x0, x - r), x1 = std::max(x1, x + r);
    }
    return fem::BoundaryPatch{name, dealii::Point<3>(x0, t.lo.y(), z),
                              dealii::Point<3>(x1, t.hi.y(), z)};
  };
  t.patches = {strip(t.pin, t.lo.z()), strip(t.roller, t.lo.z()), strip(t.loaded, t.hi.z())};
  t.pin_components = group_config(c, t.pin, where).fixed;
  t.roller_components = group_config(c, t.roller, where).fixed;
  for (const auto& [name, held] :
       {std::pair{t.pin, t.pin_components}, std::pair{t.roller, t.roller_components}})
    if (!(held & 4u))
      throw std::runtime_error("Group " + name +
                               "/fixed: a support of the bending test must hold uz");
  const auto loads = loads_on(c, t.loaded);
  if (loads.empty())
    throw std::runtime_error("Loads: no load acts on the loaded group '" + t.loaded + "'");
  for (const auto& l : loads)
  {
    if (l.load.kind != dem::LoadKind::force)
      throw std::runtime_error("Load " + l.load.name + "/type: the bending load must be a force");
    t.load_force += l.load.value;
  }
  auto points = [&](const std::string& name)
  {
    std::vector<dem::Vec3> x;
    for (int i : group_members(model, name, where).members)
      x.push_back(model.particles.reference_position[i]);
    return x;
  };
  t.top_points = points(t.loaded), t.bottom_points = points(t.bottom);
  t.mapped_groups = {t.pin, t.roller, t.loaded, t.bottom};
}

void set_material(fem::Parameters& p, const SpecimenMaterial& mat)
{
  if (mat.stiffness_tensor)
  {
    p.material = fem::MaterialModel::anisotropic;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        p.voigt_stiffness[6 * i + j] = (*mat.stiffness_tensor)(i, j);
  }
  else if (mat.shear_modulus > 0)
  {
    // cubic: compliance S11 = 1/E, S12 = -nu/E, S44 = 1/G; the normal block inverts as for the
    // isotropic material, the shear block is G.
    const double E = mat.youngs_modulus, nu = mat.poisson_ratio;
    const double c11 = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)),
                 c12 = E * nu / ((1 + nu) * (1 - 2 * nu));
    p.material = fem::MaterialModel::anisotropic;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        p.voigt_stiffness[6 * i + j] =
            i < 3 && j < 3 ? (i == j ? c11 : c12) : (i == j ? mat.shear_modulus : 0.0);
  }
  else
  {
    p.material = fem::MaterialModel::isotropic;
    p.youngs_modulus = mat.youngs_modulus;
    p.poisson_ratio = mat.poisson_ratio;
    if (!(p.youngs_modulus > 0))
      throw std::runtime_error("FE material: Young's modulus must be positive");
    if (!(p.poisson_ratio > -1.0 && p.poisson_ratio < 0.5))
      throw std::runtime_error("FE material: Poisson's ratio is outside (-1, 0.5)");
  }
}

void set_uniaxial_problem(fem::Parameters& p, const SpecimenTest& t, const json& dem_summary)
{
  const int a = t.axis;
  const auto& groups = dem_summary.at("groups");
  auto mean_u = [&](const std::string& g, int d)
  { return groups.at(g).at("mean_displacement").at(d).get<double>(); };
  std::uint8_t held_somewhere = t.fixed_components | t.loaded_held_components;
  p.boundary_constraints.push_back({t.fixed_face, component_set(t.fixed_components), 0.0});
  if (t.loaded_held_components)
    p.boundary_constraints.push_back({t.loaded_face, component_set(t.loaded_held_components), 0.0});
  if (t.displacement_control)
    for (int d = 0; d < 3; ++d)
      if (t.load_components & (1u << d))
      {
        // relative to the fixed end along the axis (the FE fixed face does not move)
        const double u = mean_u(t.loaded_group, d) - (d == a ? mean_u(t.fixed_group, a) : 0.0);
        p.boundary_constraints.push_back({t.loaded_face, component_set(1u << d), u});
        held_somewhere |= 1u << d;
      }
  if (!t.displacement_control)
    p.boundary_forces.push_back({t.loaded_face, point(t.load_force)});
  for (int d = 0; d < 3; ++d)
    if (d != a && !(held_somewhere & (1u << d)))
      p.boundary_constraints.push_back({face_name(d, false), component_set(1u << d), 0.0});
  dealii::Tensor<1, 3> e;
  e[a] = 1;
  p.reaction_boundary = t.fixed_face;
  p.reaction_direction = e;
  p.loaded_boundary = t.loaded_face;
  p.reaction_boundaries = {t.fixed_face, t.loaded_face};
}

void set_bending_problem(fem::Parameters& p, const SpecimenTest& t)
{
  p.boundary_constraints.push_back({t.pin, component_set(t.pin_components), 0.0});
  p.boundary_constraints.push_back({t.roller, component_set(t.roller_components), 0.0});
  p.boundary_forces.push_back({t.loaded, point(t.load_force)});
  p.reaction_boundaries = {t.pin, t.roller};
  auto points = [](const std::vector<dem::Vec3>& x)
  {
    std::vector<dealii::Point<3>> out;
    for (const auto& v : x)
      out.push_back(point(v));
    return out;
  };
  p.point_groups = {{"top", points(t.top_points)}, {"bottom", points(t.bottom_points)}};
}
} // namespace

SpecimenTest specimen_test(const dem::CaseConfig& c, const dem::Model& model,
                           const std::string& test)
{
  SpecimenTest t;
  std::tie(t.lo, t.hi) = dem::reference_extent(model.particles);
  t.body_lo = t.lo, t.body_hi = t.hi;
  t.n_particles = model.particles.size();
  for (double r : model.particles.radius)
    t.mean_diameter += 2 * r / double(model.particles.size());
  const auto& m = c.measure;
  const bool uniaxial = !m.modulus_fixed_group.empty(), bending = !m.flexural_groups.empty();
  t.test = test;
  if (test == "auto")
  {
    if (uniaxial == bending)
      throw std::runtime_error(
          uniaxial ? "Verification/test: the case measures both a uniaxial and a bending test; "
                     "choose one"
                   : "Measurements: verify needs 'modulus groups' (uniaxial test) or 'flexural "
                     "groups' (three-point bending); the case sets neither");
    t.test = uniaxial ? "uniaxial" : "bending";
  }
  if (t.test == "uniaxial" && !uniaxial)
    throw std::runtime_error("Measurements/modulus groups: not set (Verification/test = uniaxial)");
  if (t.test == "bending" && !bending)
    throw std::runtime_error("Measurements/flexural groups: not set (Verification/test = bending)");
  if (t.test == "uniaxial")
    read_uniaxial(t, c, model);
  else
    read_bending(t, c, model);
  for (const auto& g : c.groups)
    if (g.fixed != 0 &&
        std::find(t.mapped_groups.begin(), t.mapped_groups.end(), g.name) == t.mapped_groups.end())
      t.ignored_groups.push_back(g.name);
  return t;
}

SpecimenLayers specimen_layers(const json& dem_summary, const SpecimenTest& t, int n, int axis)
{
  SpecimenLayers l;
  if (dem_summary.contains("stress_layers"))
  {
    const auto& s = dem_summary["stress_layers"];
    const std::string a = s.value("axis", "z");
    l.axis = a.empty() ? 2 : a[0] - 'x';
    l.edges = s.at("edges").get<std::vector<double>>();
    if (l.axis < 0 || l.axis > 2 || l.edges.size() < 2)
      throw std::runtime_error("DEM summary: stress_layers has a bad axis or fewer than two edges");
    return l;
  }
  l.axis = axis;
  for (int k = 0; k <= n; ++k)
    l.edges.push_back(t.lo[axis] + (t.hi[axis] - t.lo[axis]) * k / n);
  return l;
}

fem::Parameters specimen_fe_parameters(const SpecimenTest& t, const SpecimenMaterial& material,
                                       const json& dem_summary, unsigned int degree,
                                       double cell_size, const SpecimenLayers& layers)
{
  fem::Parameters p = fem::default_parameters();
  p.problem = fem::ProblemKind::static_elasticity;
  p.degree = degree;
  std::array<unsigned, 3> n{};
  for (int d = 0; d < 3; ++d)
    n[d] = std::max(1u, unsigned(std::lround((t.body_hi[d] - t.body_lo[d]) / cell_size)));
  // Layer edges on cell faces where the body spans the slabs: a multiple of the slab count.
  const int la = layers.axis;
  const unsigned n_layers = unsigned(layers.edges.size() - 1);
  if (std::abs(t.body_lo[la] - layers.edges.front()) < 1e-9 * (t.hi - t.lo).norm() &&
      std::abs(t.body_hi[la] - layers.edges.back()) < 1e-9 * (t.hi - t.lo).norm())
    n[la] = n_layers * std::max(1u, unsigned(std::lround(double(n[la]) / n_layers)));
  p.mesh_source = fem::MeshSource::box;
  p.box_lower = point(t.body_lo);
  p.box_upper = point(t.body_hi);
  p.subdivisions = n;
  p.patches = t.patches;
  set_material(p, material);
  if (t.test == "uniaxial")
    set_uniaxial_problem(p, t, dem_summary);
  else
    set_bending_problem(p, t);
  p.stress_layer_axis = la;
  p.stress_layer_edges = layers.edges;
  p.solver_tolerance = 1e-10;
  p.write_vtu = true;
  p.base_name = "fem";
  return p;
}
} // namespace dembridge::coupling
