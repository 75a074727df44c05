// The full-DEM and full-FE models of a coupled case (see full_models.h).
#include "coupling/full_models.h"
#include "coupling/region_volume.h"
#include "dem/measurements/elasticity_tensor.h"
#include "dem/model/model.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dembridge::coupling
{
namespace
{
using dem::Vec3;
using Kind = dem::ParticleSource::Kind;

Vec3 to_vec(const dealii::Point<3>& p)
{
  return Vec3(p[0], p[1], p[2]);
}

std::uint8_t mask_of(const fem::ComponentSet& c)
{
  return std::uint8_t((c[0] ? dem::dof_ux : 0) | (c[1] ? dem::dof_uy : 0) |
                      (c[2] ? dem::dof_uz : 0));
}

std::string text(double v)
{
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

bool is_lattice(Kind k)
{
  return k == Kind::cubic || k == Kind::hcp || k == Kind::fcc;
}

bool has_volume(const Vec3& lo, const Vec3& hi)
{
  return (hi - lo).minCoeff() > 0;
}

/// A box face's support as a group of its face layer: held, or driven by its non-zero value.
SupportGroup face_support(const fem::BoundaryConstraint& face, const std::string& name)
{
  static const char* faces[6] = {"x-min", "x-max", "y-min", "y-max", "z-min", "z-max"};
  const auto it = std::find(std::begin(faces), std::end(faces), face.boundary);
  if (it == std::end(faces))
    throw std::runtime_error("FEM/Boundary conditions/boundaries: '" + face.boundary +
                             "' is not a box face; compare maps box faces, lines and points");
  const int f = int(it - std::begin(faces));
  SupportGroup g;
  g.name = name;
  g.source = "FEM/Boundary conditions/boundaries " + face.boundary;
  g.selection.kind = dem::GroupSelection::Kind::face;
  g.selection.face_axis = f / 2;
  g.selection.face_upper = f % 2 == 1;
  if (face.value != 0)
  {
    g.driven = true;
    g.driven_components = mask_of(face.components);
    for (int d = 0; d < 3; ++d)
      if (face.components[d])
        g.displacement[d] = face.value;
  }
  else
    g.fixed = mask_of(face.components);
  return g;
}
} // namespace

namespace
{
/// Refuses what compare cannot map onto a full-DEM model (packing, mesh, FE loads).
void require_mappable_to_dem(const CoupledCase& c)
{
  const auto& fe = c.continuum;
  const auto& src = c.particles.particles;
  if (!is_lattice(src.kind) && src.kind != Kind::random)
    throw std::runtime_error("Particles/source: compare extends the particle region over the FE "
                             "domain, which needs a lattice (cubic, hcp, fcc) or a random packing");
  if (fe.mesh_source != fem::MeshSource::box)
    throw std::runtime_error("FEM/Mesh/source: compare needs a box continuum (the full-DEM "
                             "specimen fills it)");
  if (!fe.boundary_forces.empty() || !fe.tractions.empty() || !fe.line_forces.empty() ||
      !fe.point_forces.empty() || fe.body_force.norm() > 0)
    throw std::runtime_error("FEM/Loads: compare maps the FE supports, not FE loads; put the "
                             "load on a particle group (Loads)");
}

/// The packing's box over the FE box: a lattice moved by whole periods, a random packing anew.
void lay_out_packing(const CoupledCase& c, const Vec3& period, FullDemLayout& layout)
{
  const auto& fe = c.continuum;
  const auto& src = c.particles.particles;
  const Vec3 lo = to_vec(fe.box_lower), hi = to_vec(fe.box_upper);
  const double r = src.radius;
  // the packing's box: a volume region's bounding box (set_particle_region), where the coupled
  // run anchors its lattice
  Vec3 src_origin = src.origin, src_size = src.box_size;
  if (!c.region_file.empty() && !c.settings.geometry.region)
  {
    const auto region = read_region_volume(c.region_file, "Coupling/particle region file");
    src_origin = region.lo();
    src_size = region.hi() - region.lo();
  }
  if (is_lattice(src.kind))
  {
    // Whole lattice periods to either side, so that the region's particles keep their places;
    // as many as keep the particle centres inside the FE box (a centre may lie on its face, as
    // the supports of a beam do).
    layout.same_packing = true;
    for (int d = 0; d < 3; ++d)
    {
      const double P = period[d], o = src_origin[d], end = o + src_size[d];
      const double below = std::max(0.0, std::floor((o - (lo[d] - r)) / P + 1e-9));
      const double above = std::max(0.0, std::floor((hi[d] + r - end) / P + 1e-9));
      layout.origin[d] = o - below * P;
      layout.box_size[d] = end + above * P - layout.origin[d];
    }
  }
  else
  {
    layout.origin = lo;
    layout.box_size = hi - lo;
    layout.notes.push_back("Particles/source: random: the full-DEM specimen is a new random "
                           "packing of the whole box (seed " +
                           std::to_string(src.seed) + "), not the coupled region's spheres");
  }
}

std::string support_name(const FullDemLayout& layout)
{
  return "support_" + std::to_string(layout.supports.size());
}

/// The FE supports as particle groups: a line holds the particles within one diameter of it, a
/// point its nearest particle, a box face its face layer (a driven face a displacement load).
void add_supports(const fem::Parameters& fe, double diameter, FullDemLayout& layout)
{
  const double inset = diameter * (1 - 1e-9);
  for (const auto& line : fe.line_constraints)
  {
    SupportGroup g;
    g.name = support_name(layout);
    g.source = "FEM/Boundary conditions/lines";
    g.selection.kind = dem::GroupSelection::Kind::box;
    const Vec3 a = to_vec(line.a), b = to_vec(line.b);
    g.selection.box_min = a.cwiseMin(b) - Vec3::Constant(inset);
    g.selection.box_max = a.cwiseMax(b) + Vec3::Constant(inset);
    g.fixed = mask_of(line.components);
    layout.supports.push_back(g);
  }
  for (const auto& point : fe.point_constraints)
  {
    SupportGroup g;
    g.name = support_name(layout);
    g.source = "FEM/Boundary conditions/points";
    g.selection.kind = dem::GroupSelection::Kind::nearest;
    g.selection.point = to_vec(point.p);
    g.fixed = mask_of(point.components);
    layout.supports.push_back(g);
  }
  for (const auto& face : fe.boundary_constraints)
    layout.supports.push_back(face_support(face, support_name(layout)));
  if (layout.supports.empty())
    throw std::runtime_error("FEM/Boundary conditions: the continuum has no support, so the "
                             "full-DEM model would have none");
}

/// Builds the full-DEM case (its supports select particles) and says where a lattice's centres
/// stop short of the FE box's faces.
void check_lattice_reaches_box(const CoupledCase& c, const Vec3& period, FullDemLayout& layout)
{
  const Vec3 lo = to_vec(c.continuum.box_lower), hi = to_vec(c.continuum.box_upper);
  const double r = c.particles.particles.radius;
  const dem::Model m = dem::build_model(full_dem_case(c, layout));
  if (!is_lattice(c.particles.particles.kind))
    return;
  Vec3 first = Vec3::Constant(std::numeric_limits<double>::max()), last = -first;
  for (std::size_t i = 0; i < m.particles.size(); ++i)
    first = first.cwiseMin(m.particles.position[i]), last = last.cwiseMax(m.particles.position[i]);
  for (int d = 0; d < 3; ++d)
    if (first[d] - lo[d] > 1.5 * r || hi[d] - last[d] > 1.5 * r)
      layout.notes.push_back(std::string("Particles/origin: the region's lattice (period ") +
                             text(period[d]) + " m along " + "xyz"[d] +
                             ") does not fill the FE box: the full-DEM particle centres "
                             "span " +
                             text(first[d]) + " to " + text(last[d]) + " m, the FE box " +
                             text(lo[d]) + " to " + text(hi[d]) +
                             " m (choose the origin so that whole periods reach the FE "
                             "box's faces)");
}
} // namespace

FullDemLayout full_dem_layout(const CoupledCase& c)
{
  require_mappable_to_dem(c);
  const auto& src = c.particles.particles;
  FullDemLayout layout;
  const Vec3 period =
      is_lattice(src.kind) ? dem::lattice_axis_periods(src.kind, src.radius) : Vec3::Zero();
  lay_out_packing(c, period, layout);
  add_supports(c.continuum, 2 * src.radius, layout);
  layout.mass_damping = c.settings.mass_damping;
  check_lattice_reaches_box(c, period, layout);
  if (c.settings.fine_scale_damping > 0)
    layout.notes.push_back("Coupling/fine scale damping: acts in the band only; the full-DEM "
                           "run has no counterpart");
  return layout;
}

dem::CaseConfig full_dem_case(const CoupledCase& c, const FullDemLayout& layout)
{
  dem::CaseConfig full = c.particles;
  full.particles.keep = nullptr; // the whole specimen, not the coupled run's region
  full.particles.origin = layout.origin;
  full.particles.box_size = layout.box_size;
  full.run.mass_damping = layout.mass_damping;
  for (const auto& s : layout.supports)
  {
    dem::GroupConfig g;
    g.name = s.name;
    g.selection = s.selection;
    g.fixed = s.fixed;
    full.groups.push_back(g);
    if (s.driven)
    {
      dem::LoadConfig load;
      load.group = s.name;
      load.load.name = s.name;
      load.load.kind = dem::LoadKind::displacement;
      load.load.value = s.displacement;
      load.load.components = s.driven_components;
      load.load.ramp_time = c.ramp_time;
      load.load.profile = c.smooth_ramp ? dem::RampProfile::smooth : dem::RampProfile::linear;
      full.loads.push_back(load);
    }
  }
  return full;
}

namespace
{
/// The FE reference's own settings: static, the region's tensor, cells of about @p cell_size.
void set_reference_continuum(const CoupledCase& c, double cell_size, unsigned int degree,
                             fem::Parameters& p)
{
  p = c.continuum;
  if (p.mesh_source != fem::MeshSource::box)
    throw std::runtime_error("FEM/Mesh/source: compare needs a box continuum");
  if (!(cell_size > 0))
    throw std::runtime_error("compare: the FE cell size must be positive");
  p.problem = fem::ProblemKind::static_elasticity;
  p.degree = degree;
  p.incompatible_modes = false; // the reference's own cells: Q2 by default, static
  p.material = fem::MaterialModel::anisotropic;
  p.voigt_stiffness = continuum_tensor(c);
  for (int d = 0; d < 3; ++d)
    p.subdivisions[d] =
        unsigned(std::max(1L, std::lround((p.box_upper[d] - p.box_lower[d]) / cell_size)));
  p.refinements = 0;
}

/// The notch (Particles/remove box) as the box of the spheres it removed, cut out of the mesh;
/// the region's particles without removal say where they were.
void cut_out_notch(const dem::CaseConfig& region, fem::Parameters& p)
{
  const auto& src = region.particles;
  if (!has_volume(src.remove_box_min, src.remove_box_max))
    return;
  const double r = src.radius;
  const Vec3 lo = to_vec(p.box_lower), hi = to_vec(p.box_upper);
  dem::CaseConfig whole = region;
  whole.particles.remove_box_min = whole.particles.remove_box_max = Vec3::Zero();
  whole.groups.clear();
  whole.loads.clear();
  whole.measure = {};
  const dem::Model m = dem::build_model(whole);
  Vec3 a = Vec3::Constant(std::numeric_limits<double>::max()), b = -a;
  for (std::size_t i = 0; i < m.particles.size(); ++i)
  {
    const Vec3& x = m.particles.position[i];
    if ((x - src.remove_box_min).minCoeff() > 0 && (src.remove_box_max - x).minCoeff() > 0)
    {
      a = a.cwiseMin(x - Vec3::Constant(m.particles.radius[i]));
      b = b.cwiseMax(x + Vec3::Constant(m.particles.radius[i]));
    }
  }
  if (!has_volume(a, b))
    return;
  // a void that reaches a face of the specimen opens to the outside of the FE box
  for (int d = 0; d < 3; ++d)
  {
    if (a[d] <= lo[d] + 1e-6 * r)
      a[d] = lo[d] - r;
    if (b[d] >= hi[d] - 1e-6 * r)
      b[d] = hi[d] + r;
  }
  p.remove_lower = dealii::Point<3>(a[0], a[1], a[2]);
  p.remove_upper = dealii::Point<3>(b[0], b[1], b[2]);
}

/// The case's one displacement load on a particle group.
const dem::LoadConfig& displacement_load(const dem::CaseConfig& region)
{
  const dem::LoadConfig* load = nullptr;
  for (const auto& l : region.loads)
    if (l.load.kind == dem::LoadKind::displacement)
    {
      if (load)
        throw std::runtime_error("Loads: compare models one displacement load in the FE "
                                 "reference; the case has more");
      load = &l;
    }
  if (!load)
    throw std::runtime_error("Loads: compare needs a displacement load on a particle group (the "
                             "displacement control the FE reference reproduces)");
  return *load;
}

/// The FE boundary patch under the loaded group: its spheres' box, flattened onto the FE box
/// face it touches along a loaded component.
fem::BoundaryPatch load_patch(const dem::CaseConfig& region, const dem::LoadConfig& load,
                              const fem::Parameters& p)
{
  const double r = region.particles.radius;
  const Vec3 lo = to_vec(p.box_lower), hi = to_vec(p.box_upper);
  const dem::Model m = dem::build_model(region);
  const auto& members = m.groups[m.group_index(load.group, "Load " + load.load.name)].members;
  Vec3 a = Vec3::Constant(std::numeric_limits<double>::max()), b = -a;
  for (int i : members)
  {
    a = a.cwiseMin(m.particles.position[i] - Vec3::Constant(m.particles.radius[i]));
    b = b.cwiseMax(m.particles.position[i] + Vec3::Constant(m.particles.radius[i]));
  }
  const Vec3 value = load.load.value;
  const std::uint8_t comps = load.load.components;
  int axis = -1; // the face normal: the loaded component the group touches a face along
  for (int d = 0; d < 3 && axis < 0; ++d)
    if ((comps & (1u << d)) && value[d] != 0 &&
        (std::abs(b[d] - hi[d]) < 1e-6 * r || std::abs(a[d] - lo[d]) < 1e-6 * r))
      axis = d;
  if (axis < 0)
    throw std::runtime_error("Load " + load.load.name + ": compare needs the loaded group '" +
                             load.group +
                             "' to touch a face of the FE box along a loaded "
                             "component");
  const bool upper = std::abs(b[axis] - hi[axis]) < 1e-6 * r;
  const double face = upper ? hi[axis] : lo[axis];
  a[axis] = face - 1e-3 * r;
  b[axis] = face + 1e-3 * r;
  fem::BoundaryPatch patch;
  patch.name = "load";
  patch.lower = dealii::Point<3>(a[0], a[1], a[2]);
  patch.upper = dealii::Point<3>(b[0], b[1], b[2]);
  return patch;
}

/// The patch's prescribed displacement (one value for every loaded component) in @p p, and the
/// reference's outputs: the reaction on the patch, no other measurement.
void prescribe_load(const dem::LoadConfig& load, FeLoadPatch& patch, fem::Parameters& p)
{
  const Vec3 value = load.load.value;
  const std::uint8_t comps = load.load.components;
  double shared = 0;
  for (int d = 0; d < 3; ++d)
    if (comps & (1u << d))
    {
      if (shared != 0 && value[d] != shared)
        throw std::runtime_error("Load " + load.load.name +
                                 ": the FE reference prescribes one "
                                 "value for every loaded component");
      shared = value[d];
    }
  patch.displacement = Vec3::Zero();
  for (int d = 0; d < 3; ++d)
    if (comps & (1u << d))
      patch.displacement[d] = value[d];
  patch.direction = patch.displacement.normalized();
  p.patches.push_back(patch.patch);
  p.fit_planes = true;
  fem::BoundaryConstraint prescribed;
  prescribed.boundary = "load";
  prescribed.components = {{bool(comps & 1u), bool(comps & 2u), bool(comps & 4u)}};
  prescribed.value = shared;
  p.boundary_constraints.push_back(prescribed);
  p.reaction_boundaries = {"load"};
  p.reaction_boundary.clear();
  p.loaded_boundary.clear();
  p.deflection_points.clear();
  p.point_groups.clear();
  p.stress_layer_axis = -1;
  p.base_name = "fem";
}
} // namespace

FullFeModel full_fe_model(const CoupledCase& c, double cell_size, unsigned int degree)
{
  FullFeModel model;
  fem::Parameters& p = model.parameters;
  set_reference_continuum(c, cell_size, degree, p);
  const dem::CaseConfig& region = c.particles;
  cut_out_notch(region, p);
  // The load: the (one) displacement load on a particle group, on the FE face it touches.
  const dem::LoadConfig& load = displacement_load(region);
  model.load.group = load.group;
  model.load.patch = load_patch(region, load, p);
  model.load.components = load.load.components;
  prescribe_load(load, model.load, p);
  model.notes.push_back("the FE reference is elastic: its load-deflection line is the initial "
                        "stiffness, with no peak");
  return model;
}
} // namespace dembridge::coupling
