// dembridge::fem — declaration and parsing of the FEM parameter subsections.
#include "parameters.h"
#include "dem/core/number_list.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace dembridge::fem
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

namespace
{
std::string trim(const std::string& s)
{
  const auto first = s.find_first_not_of(" \t\n");
  if (first == std::string::npos)
    return "";
  const auto last = s.find_last_not_of(" \t\n");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& s, const char separator)
{
  std::vector<std::string> parts;
  std::stringstream in(s);
  std::string part;
  while (std::getline(in, part, separator))
    if (!trim(part).empty())
      parts.push_back(trim(part));
  return parts;
}

[[noreturn]] void fail(const std::string& where, const std::string& why)
{
  throw std::runtime_error(where + ": " + why);
}

double to_double(const std::string& text, const std::string& where)
{
  try
  {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(value))
      fail(where, "'" + text + "' is not a number");
    return value;
  }
  catch (const std::logic_error&)
  {
    fail(where, "'" + text + "' is not a number");
  }
}

Tensor<1, 3> parse_vector(const std::string& text, const std::string& where)
{
  const Point<3> p = parse_point(text, where);
  return p;
}

ComponentSet parse_components(const std::string& text, const std::string& where)
{
  ComponentSet set{{false, false, false}};
  if (text.empty())
    fail(where, "no displacement components given (use letters x, y, z)");
  for (const char c : text)
  {
    if (c < 'x' || c > 'z')
      fail(where, "'" + text + "' is not a set of components (use letters x, y, z)");
    set[c - 'x'] = true;
  }
  return set;
}

/// "HEAD: TAIL" -> {HEAD, TAIL}
std::pair<std::string, std::string> split_colon(const std::string& item, const std::string& where)
{
  const auto colon = item.rfind(':');
  if (colon == std::string::npos)
    fail(where, "'" + item + "' lacks ':'");
  return {trim(item.substr(0, colon)), trim(item.substr(colon + 1))};
}

/// "X,Y,Z to X,Y,Z" -> segment
std::pair<Point<3>, Point<3>> parse_segment(const std::string& text, const std::string& where)
{
  const auto to = text.find(" to ");
  if (to == std::string::npos)
    fail(where, "'" + text + "' is not a segment 'X,Y,Z to X,Y,Z'");
  return {parse_point(trim(text.substr(0, to)), where),
          parse_point(trim(text.substr(to + 4)), where)};
}

std::vector<Point<3>> parse_point_list(const std::string& text, const std::string& where)
{
  std::vector<Point<3>> points;
  for (const auto& item : split(text, ';'))
    points.push_back(parse_point(item, where));
  return points;
}

std::vector<BoundaryLoad> parse_boundary_loads(const std::string& text, const std::string& where)
{
  std::vector<BoundaryLoad> loads;
  for (const auto& item : split(text, ';'))
  {
    const auto [name, vector] = split_colon(item, where);
    loads.push_back({name, parse_vector(vector, where)});
  }
  return loads;
}
} // namespace

Point<3> parse_point(const std::string& text, const std::string& where)
{
  const dem::Vec3 v = dem::parse_vec3(text, where);
  return Point<3>(v[0], v[1], v[2]);
}

void declare_fem_parameters(ParameterHandler& prm)
{
  prm.enter_subsection("FEM");
  {
    prm.declare_entry("problem", "static", Patterns::Selection("static|dynamics"),
                      "static: linear elasticity, one solve (CG + BoomerAMG). dynamics: explicit "
                      "central differences with a lumped mass matrix.");
    prm.declare_entry("degree", "1", Patterns::Integer(1, 2),
                      "Polynomial degree of the vector FE_Q displacement element.");
    prm.declare_entry("incompatible modes", "false", Patterns::Bool(),
                      "Degree 1 only, explicit dynamics and coupled runs: enrich each cell by "
                      "the nine bubble modes of Wilson's incompatible element, condensed out "
                      "(Taylor et al. 1976), so that beams of a few cells through the depth do "
                      "not lock in bending. Written stresses and strains are those of the nodal "
                      "(compatible) field.");

    prm.enter_subsection("Mesh");
    prm.declare_entry("source", "box", Patterns::Selection("box|gmsh"),
                      "box: subdivided hyper-rectangle with faces x-min, x-max, y-min, y-max, "
                      "z-min, z-max. gmsh: hexahedral .msh file with named physical groups.");
    prm.declare_entry("file", "", Patterns::Anything(),
                      "Path of the gmsh .msh file (source = gmsh). A relative path is relative "
                      "to the case file's folder (dembridge run works there); if no such file "
                      "exists, the file of that name in the build's meshes folder (where "
                      "meshes/*.geo are meshed) is used.");
    prm.declare_entry("box lower", "0,0,0", Patterns::List(Patterns::Double(), 3, 3),
                      "Lower corner of the box (m).");
    prm.declare_entry("box upper", "0.25,0.1,0.1", Patterns::List(Patterns::Double(), 3, 3),
                      "Upper corner of the box (m).");
    prm.declare_entry("box subdivisions", "5,2,2",
                      Patterns::List(Patterns::Integer(1, 10000), 3, 3),
                      "Number of cells of the coarse box along x, y, z.");
    prm.declare_entry("refinements", "0", Patterns::Integer(0, 10),
                      "Number of global refinements of the coarse mesh (each halves h).");
    prm.declare_entry("remove box", "", Patterns::Anything(),
                      "'X,Y,Z to X,Y,Z' (box meshes): the cells inside are left out, e.g. a "
                      "notch; its faces form the boundary 'removed'. The box's planes are mesh "
                      "planes (fit planes is implied).");
    prm.declare_entry("fit planes", "false", Patterns::Bool(),
                      "Box meshes: put cell faces on the planes of every patch (and of the "
                      "remove box), dividing the intervals between them evenly to about the "
                      "size the subdivisions give, so that a patch is resolved exactly.");
    prm.declare_entry("patches", "", Patterns::Anything(),
                      "'NAME: X,Y,Z to X,Y,Z; ...': the boundary faces (after refinement) whose "
                      "centres lie in the box become the boundary NAME, e.g. a support strip "
                      "'pin: 0,0,0 to 0.01,0.1,0'.");
    prm.leave_subsection();

    prm.enter_subsection("Material");
    prm.declare_entry("model", "isotropic", Patterns::Selection("isotropic|anisotropic"),
                      "isotropic: youngs modulus, poisson ratio. anisotropic: voigt stiffness.");
    prm.declare_entry("youngs modulus", "4e9", Patterns::Double(0),
                      "Young's modulus E (Pa), isotropic model.");
    prm.declare_entry("poisson ratio", "0.3", Patterns::Double(-1, 0.5),
                      "Poisson's ratio nu, strictly inside (-1, 0.5), isotropic model.");
    prm.declare_entry("density", "925", Patterns::Double(0), "Mass density (kg/m^3).");
    prm.declare_entry("voigt stiffness", "", Patterns::Anything(),
                      "36 comma-separated entries (Pa) of the symmetric 6x6 stiffness in Voigt "
                      "order xx, yy, zz, yz, xz, xy (engineering shear strains), row by row; "
                      "anisotropic model.");
    prm.leave_subsection();

    prm.enter_subsection("Boundary conditions");
    prm.declare_entry("boundaries", "", Patterns::Anything(),
                      "Dirichlet faces: 'NAME: COMPONENTS [= VALUE]; ...', e.g. 'x-min: xyz; "
                      "x-max: x = -1e-5'. NAME is a box face or gmsh physical group.");
    prm.declare_entry("lines", "", Patterns::Anything(),
                      "Support lines: 'X,Y,Z to X,Y,Z: COMPONENTS; ...'; every node on the "
                      "segment is fixed in the listed components (thesis pin/roller lines).");
    prm.declare_entry("points", "", Patterns::Anything(),
                      "Support points: 'X,Y,Z: COMPONENTS; ...'; the node at the point is fixed.");
    prm.leave_subsection();

    prm.enter_subsection("Loads");
    prm.declare_entry("boundary forces", "", Patterns::Anything(),
                      "'NAME: FX,FY,FZ; ...': total force (N) spread as a uniform traction.");
    prm.declare_entry("tractions", "", Patterns::Anything(),
                      "'NAME: TX,TY,TZ; ...': traction (Pa) on a boundary.");
    prm.declare_entry("line forces", "", Patterns::Anything(),
                      "'X,Y,Z to X,Y,Z: FX,FY,FZ; ...': total force (N) uniformly along a "
                      "segment that lies on mesh edges (consistent nodal forces).");
    prm.declare_entry("point forces", "", Patterns::Anything(),
                      "'X,Y,Z: FX,FY,FZ; ...': force (N) on the node nearest to the point.");
    prm.declare_entry("body force", "0,0,0", Patterns::List(Patterns::Double(), 3, 3),
                      "Body force density (N/m^3), e.g. 0,0,-rho*g.");
    prm.leave_subsection();

    prm.enter_subsection("Solver");
    prm.declare_entry("tolerance", "1e-10", Patterns::Double(1e-16, 1e-2),
                      "CG stops when the residual falls below tolerance * |rhs|.");
    prm.declare_entry("max iterations", "2000", Patterns::Integer(1, 1000000),
                      "Maximum number of CG iterations.");
    prm.declare_entry("amg strong threshold", "0.5", Patterns::Double(0, 1),
                      "BoomerAMG strong threshold (0.5 suits 3D elasticity).");
    prm.leave_subsection();

    prm.enter_subsection("Dynamics");
    prm.declare_entry("steps", "1000", Patterns::Integer(1, 100000000),
                      "Number of central-difference steps.");
    prm.declare_entry("time step factor", "0.9", Patterns::Double(0, 1),
                      "Time step as a fraction of the stable step 2/omega_max (Gershgorin "
                      "bound of M^-1 K).");
    prm.declare_entry("initial displacement", "0; 0; 0", Patterns::Anything(),
                      "Initial displacement u_x; u_y; u_z as muparser expressions of x, y, z "
                      "(constant pi available); initial velocity is zero.");
    prm.declare_entry("probe points", "", Patterns::Anything(),
                      "'X,Y,Z; ...': points whose displacement goes into history.csv.");
    prm.leave_subsection();

    prm.enter_subsection("Measurements");
    prm.declare_entry("deflection name", "midspan_deflection", Patterns::Anything(),
                      "summary.json key of the deflection (snake_case).");
    prm.declare_entry("deflection points", "", Patterns::Anything(),
                      "'X,Y,Z; ...': the deflection is the mean of u . direction over them.");
    prm.declare_entry("deflection direction", "0,0,-1", Patterns::List(Patterns::Double(), 3, 3),
                      "Unit direction in which deflection is counted positive.");
    prm.declare_entry("reaction boundary", "", Patterns::Anything(),
                      "Dirichlet boundary whose reaction force goes into the summary.");
    prm.declare_entry("reaction direction", "1,0,0", Patterns::List(Patterns::Double(), 3, 3),
                      "reaction_force is the reaction's component along this direction.");
    prm.declare_entry("loaded boundary", "", Patterns::Anything(),
                      "If set with the reaction boundary: youngs_modulus = (R/A) / (du/L0), "
                      "du and L0 the mean displacement and centroid distance between the two "
                      "boundaries along the reaction direction, A the reaction boundary area.");
    prm.declare_entry("reaction boundaries", "", Patterns::Anything(),
                      "'NAME, NAME, ...': boundaries whose reaction vectors go into the summary "
                      "(reactions.NAME, N; the force of the support on the body).");
    prm.declare_entry("point groups", "", Patterns::Anything(),
                      "'NAME: X,Y,Z; X,Y,Z | NAME: ...': mean displacement over each set of "
                      "points (mean_displacements.NAME, m).");
    prm.declare_entry("stress layers", "", Patterns::Anything(),
                      "'AXIS: E0, E1, ..., EN' (AXIS x, y or z): volume averages of the stress "
                      "over the slabs E(k) <= AXIS < E(k+1), by quadrature point "
                      "(stress_layers: edges, volume, sigma).");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("vtu", "true", Patterns::Bool(), "Write .vtu/.pvtu/.pvd files.");
    prm.declare_entry("base name", "fem", Patterns::FileName(), "Prefix of the output files.");
    prm.declare_entry("every", "0", Patterns::Integer(0),
                      "Dynamics: write fields every N steps (0: first and last only).");
    prm.leave_subsection();
  }
  prm.leave_subsection();
}

Parameters parse_parameters(const ParameterHandler& prm)
{
  using Path = std::vector<std::string>;
  Parameters p;
  const Path fem{"FEM"};
  p.problem = prm.get(fem, "problem") == "static" ? ProblemKind::static_elasticity
                                                  : ProblemKind::explicit_dynamics;
  p.degree = prm.get_integer(fem, "degree");
  p.incompatible_modes = prm.get_bool(fem, "incompatible modes");
  if (p.incompatible_modes && p.degree != 1)
    fail("FEM/incompatible modes", "the incompatible modes enrich degree 1 cells only (FEM/degree "
                                   "is " +
                                       std::to_string(p.degree) + ")");

  const Path mesh{"FEM", "Mesh"};
  p.mesh_source = prm.get(mesh, "source") == "box" ? MeshSource::box : MeshSource::gmsh;
  p.mesh_file = trim(prm.get(mesh, "file"));
  if (p.mesh_source == MeshSource::gmsh && p.mesh_file.empty())
    fail("FEM/Mesh/file", "no mesh file given for source = gmsh");
  p.box_lower = parse_point(prm.get(mesh, "box lower"), "FEM/Mesh/box lower");
  p.box_upper = parse_point(prm.get(mesh, "box upper"), "FEM/Mesh/box upper");
  for (unsigned int d = 0; d < 3; ++d)
    if (!(p.box_upper[d] > p.box_lower[d]))
      fail("FEM/Mesh/box upper", "must exceed box lower in every coordinate");
  const auto subdivisions = split(prm.get(mesh, "box subdivisions"), ',');
  for (unsigned int d = 0; d < 3; ++d)
    p.subdivisions[d] = std::stoul(subdivisions[d]);
  p.refinements = prm.get_integer(mesh, "refinements");
  for (const auto& item : split(prm.get(mesh, "patches"), ';'))
  {
    const std::string where = "FEM/Mesh/patches";
    const auto colon = item.find(':');
    if (colon == std::string::npos)
      fail(where, "'" + item + "' lacks ':'");
    BoundaryPatch patch;
    patch.name = trim(item.substr(0, colon));
    if (patch.name.empty())
      fail(where, "'" + item + "' has no name");
    std::tie(patch.lower, patch.upper) = parse_segment(trim(item.substr(colon + 1)), where);
    for (unsigned int d = 0; d < 3; ++d)
      if (patch.upper[d] < patch.lower[d])
        fail(where, "patch '" + patch.name + "': upper corner below lower corner");
    p.patches.push_back(patch);
  }

  if (const std::string remove = trim(prm.get(mesh, "remove box")); !remove.empty())
  {
    const std::string where = "FEM/Mesh/remove box";
    if (p.mesh_source != MeshSource::box)
      fail(where, "only a box mesh (FEM/Mesh/source = box) can have cells removed");
    std::tie(p.remove_lower, p.remove_upper) = parse_segment(remove, where);
    for (unsigned int d = 0; d < 3; ++d)
      if (!(p.remove_upper[d] > p.remove_lower[d]))
        fail(where, "the upper corner must exceed the lower one in every coordinate");
    bool inside = true;
    for (unsigned int d = 0; d < 3; ++d)
      inside = inside && p.remove_upper[d] > p.box_lower[d] && p.remove_lower[d] < p.box_upper[d];
    if (!inside)
      fail(where, "the box does not overlap the mesh box");
  }
  p.fit_planes = prm.get_bool(mesh, "fit planes");

  const Path material{"FEM", "Material"};
  p.material = prm.get(material, "model") == "isotropic" ? MaterialModel::isotropic
                                                         : MaterialModel::anisotropic;
  p.youngs_modulus = prm.get_double(material, "youngs modulus");
  p.poisson_ratio = prm.get_double(material, "poisson ratio");
  p.density = prm.get_double(material, "density");
  if (p.material == MaterialModel::isotropic)
  {
    if (!(p.youngs_modulus > 0))
      fail("FEM/Material/youngs modulus", "must be positive");
    if (!(p.poisson_ratio > -1.0 && p.poisson_ratio < 0.5))
      fail("FEM/Material/poisson ratio", std::to_string(p.poisson_ratio) + " is outside (-1, 0.5)");
  }
  else
  {
    const std::string where = "FEM/Material/voigt stiffness";
    const auto entries = split(prm.get(material, "voigt stiffness"), ',');
    if (entries.size() != 36)
      fail(where, "needs 36 entries, got " + std::to_string(entries.size()));
    for (unsigned int i = 0; i < 36; ++i)
      p.voigt_stiffness[i] = to_double(entries[i], where);
  }

  const Path bc{"FEM", "Boundary conditions"};
  {
    const std::string where = "FEM/Boundary conditions/boundaries";
    for (const auto& item : split(prm.get(bc, "boundaries"), ';'))
    {
      const auto colon = item.find(':');
      if (colon == std::string::npos)
        fail(where, "'" + item + "' lacks ':'");
      BoundaryConstraint c;
      c.boundary = trim(item.substr(0, colon));
      std::string rest = trim(item.substr(colon + 1));
      if (const auto eq = rest.find('='); eq != std::string::npos)
      {
        c.value = to_double(trim(rest.substr(eq + 1)), where);
        rest = trim(rest.substr(0, eq));
      }
      c.components = parse_components(rest, where);
      p.boundary_constraints.push_back(c);
    }
  }
  {
    const std::string where = "FEM/Boundary conditions/lines";
    for (const auto& item : split(prm.get(bc, "lines"), ';'))
    {
      const auto [segment, components] = split_colon(item, where);
      const auto [a, b] = parse_segment(segment, where);
      p.line_constraints.push_back({a, b, parse_components(components, where)});
    }
  }
  {
    const std::string where = "FEM/Boundary conditions/points";
    for (const auto& item : split(prm.get(bc, "points"), ';'))
    {
      const auto [point, components] = split_colon(item, where);
      p.point_constraints.push_back(
          {parse_point(point, where), parse_components(components, where)});
    }
  }

  const Path loads{"FEM", "Loads"};
  p.boundary_forces =
      parse_boundary_loads(prm.get(loads, "boundary forces"), "FEM/Loads/boundary forces");
  p.tractions = parse_boundary_loads(prm.get(loads, "tractions"), "FEM/Loads/tractions");
  for (const auto& item : split(prm.get(loads, "line forces"), ';'))
  {
    const std::string where = "FEM/Loads/line forces";
    const auto [segment, force] = split_colon(item, where);
    const auto [a, b] = parse_segment(segment, where);
    if (a.distance(b) == 0.0)
      fail(where, "segment '" + segment + "' has zero length");
    p.line_forces.push_back({a, b, parse_vector(force, where)});
  }
  for (const auto& item : split(prm.get(loads, "point forces"), ';'))
  {
    const std::string where = "FEM/Loads/point forces";
    const auto [point, force] = split_colon(item, where);
    p.point_forces.push_back({parse_point(point, where), parse_vector(force, where)});
  }
  p.body_force = parse_vector(prm.get(loads, "body force"), "FEM/Loads/body force");

  const Path solver{"FEM", "Solver"};
  p.solver_tolerance = prm.get_double(solver, "tolerance");
  p.max_iterations = prm.get_integer(solver, "max iterations");
  p.amg_strong_threshold = prm.get_double(solver, "amg strong threshold");

  const Path dynamics{"FEM", "Dynamics"};
  p.n_steps = prm.get_integer(dynamics, "steps");
  p.time_step_factor = prm.get_double(dynamics, "time step factor");
  if (!(p.time_step_factor > 0))
    fail("FEM/Dynamics/time step factor", "must be positive");
  p.initial_displacement = prm.get(dynamics, "initial displacement");
  if (split(p.initial_displacement, ';').size() != 3)
    fail("FEM/Dynamics/initial displacement", "needs three expressions separated by ';'");
  p.probe_points = parse_point_list(prm.get(dynamics, "probe points"), "FEM/Dynamics/probe points");

  const Path measure{"FEM", "Measurements"};
  p.deflection_name = trim(prm.get(measure, "deflection name"));
  p.deflection_points =
      parse_point_list(prm.get(measure, "deflection points"), "FEM/Measurements/deflection points");
  p.deflection_direction = parse_vector(prm.get(measure, "deflection direction"),
                                        "FEM/Measurements/deflection direction");
  p.reaction_boundary = trim(prm.get(measure, "reaction boundary"));
  p.reaction_direction =
      parse_vector(prm.get(measure, "reaction direction"), "FEM/Measurements/reaction direction");
  p.loaded_boundary = trim(prm.get(measure, "loaded boundary"));
  p.reaction_boundaries = split(prm.get(measure, "reaction boundaries"), ',');
  for (const auto& group : split(prm.get(measure, "point groups"), '|'))
  {
    const std::string where = "FEM/Measurements/point groups";
    const auto colon = group.find(':');
    if (colon == std::string::npos)
      fail(where, "'" + group + "' lacks ':'");
    PointGroup g{trim(group.substr(0, colon)), parse_point_list(group.substr(colon + 1), where)};
    if (g.name.empty() || g.points.empty())
      fail(where, "'" + group + "' needs a name and at least one point");
    p.point_groups.push_back(g);
  }
  if (const std::string layers = trim(prm.get(measure, "stress layers")); !layers.empty())
  {
    const std::string where = "FEM/Measurements/stress layers";
    const auto colon = layers.find(':');
    const std::string axis = colon == std::string::npos ? "" : trim(layers.substr(0, colon));
    if (axis.size() != 1 || axis[0] < 'x' || axis[0] > 'z')
      fail(where, "expected 'AXIS: E0, E1, ...' with AXIS x, y or z");
    p.stress_layer_axis = axis[0] - 'x';
    for (const auto& edge : split(layers.substr(colon + 1), ','))
      p.stress_layer_edges.push_back(to_double(edge, where));
    if (p.stress_layer_edges.size() < 2)
      fail(where, "needs at least two edges");
    for (std::size_t k = 1; k < p.stress_layer_edges.size(); ++k)
      if (!(p.stress_layer_edges[k] > p.stress_layer_edges[k - 1]))
        fail(where, "edges must increase");
  }
  if (p.deflection_direction.norm() == 0 || p.reaction_direction.norm() == 0)
    fail("FEM/Measurements", "directions must be non-zero");
  p.deflection_direction /= p.deflection_direction.norm();
  p.reaction_direction /= p.reaction_direction.norm();

  const Path output{"FEM", "Output"};
  p.write_vtu = prm.get_bool(output, "vtu");
  p.base_name = prm.get(output, "base name");
  p.output_every = prm.get_integer(output, "every");
  return p;
}

} // namespace dembridge::fem
