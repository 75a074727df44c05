// dembridge::fem — the parameters of a continuum case, parsed once from a ParameterHandler.
//
// Every FEM subsection is declared here (declare_parameters) and read into plain structs
// (parse_parameters) so that the solvers never touch strings. Lists of boundary conditions and
// loads use a small text syntax, documented beside each entry and in docs/fem.md:
//   boundary constraint : NAME: COMPONENTS [= VALUE]          e.g. "x-max: x = -1e-5"
//   line constraint     : X,Y,Z to X,Y,Z: COMPONENTS          e.g. "0,0,0 to 0,0.1,0: yz"
//   point constraint    : X,Y,Z: COMPONENTS                   e.g. "0,0,0: xyz"
//   boundary force      : NAME: FX,FY,FZ                      (total force, spread uniformly)
//   traction            : NAME: TX,TY,TZ                      (force per area, Pa)
//   line force          : X,Y,Z to X,Y,Z: FX,FY,FZ            (total force along the segment)
//   point force         : X,Y,Z: FX,FY,FZ                     (force on the nearest node)
// Entries of one list are separated by ';'. NAME is a box face (x-min, x-max, y-min, y-max,
// z-min, z-max) or a gmsh physical group name.
#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <string>
#include <vector>

namespace dembridge::fem
{
using dealii::Point;
using dealii::Tensor;

/// Which displacement components a constraint fixes (x, y, z).
using ComponentSet = std::array<bool, 3>;

struct BoundaryConstraint
{
  std::string boundary;
  ComponentSet components;
  double value = 0.0; ///< prescribed displacement of every listed component (m)
};

struct LineConstraint
{
  Point<3> a, b; ///< segment end points; nodes within a small tolerance of it are fixed
  ComponentSet components;
};

struct PointConstraint
{
  Point<3> p;
  ComponentSet components;
};

struct BoundaryLoad
{
  std::string boundary;
  Tensor<1, 3> vector; ///< total force (N) or traction (Pa), see the list it belongs to
};

struct LineLoad
{
  Point<3> a, b;
  Tensor<1, 3> force; ///< total force (N), distributed uniformly along the segment
};

/// Boundary faces whose centres lie in the box [lower, upper] form the named boundary NAME
/// (taken away from the face or group they belonged to), e.g. a support strip of a box mesh.
struct BoundaryPatch
{
  std::string name;
  Point<3> lower, upper;
};

/// Named set of points; its mean displacement goes into the summary.
struct PointGroup
{
  std::string name;
  std::vector<Point<3>> points;
};

struct PointLoad
{
  Point<3> p;
  Tensor<1, 3> force; ///< N, applied to the nearest node
};

enum class MeshSource
{
  box,  ///< GridGenerator::subdivided_hyper_rectangle, faces named x-min ... z-max
  gmsh, ///< a .msh file (format 2.2 or 4.1, hexahedra) with named physical groups
};

enum class MaterialModel
{
  isotropic,   ///< Young's modulus and Poisson's ratio
  anisotropic, ///< full 6x6 Voigt stiffness matrix
};

enum class ProblemKind
{
  static_elasticity, ///< one linear solve
  explicit_dynamics, ///< central differences with a lumped mass matrix
};

struct Parameters
{
  // FEM
  ProblemKind problem = ProblemKind::static_elasticity;
  unsigned int degree = 1;
  /// Q1 cells enriched by condensed incompatible modes (incompatible_modes.h): no shear locking
  /// in bending; explicit dynamics and coupled runs only.
  bool incompatible_modes = false;
  // FEM/Mesh
  MeshSource mesh_source = MeshSource::box;
  std::string mesh_file;
  Point<3> box_lower, box_upper;
  std::array<unsigned int, 3> subdivisions{{1, 1, 1}};
  unsigned int refinements = 0;
  std::vector<BoundaryPatch> patches;
  /// Box meshes: cells inside [remove_lower, remove_upper] are left out (a notch); its new
  /// faces form the boundary "removed". No removal while the box has no volume.
  Point<3> remove_lower, remove_upper;
  /// Box meshes: cell faces are placed on the planes of the remove box and of every patch that
  /// cut the box, the intervals between them divided evenly to about the subdivisions' size.
  bool fit_planes = false;
  // FEM/Material
  MaterialModel material = MaterialModel::isotropic;
  double youngs_modulus = 1.0;
  double poisson_ratio = 0.0;
  double density = 1.0;
  std::array<double, 36> voigt_stiffness{};
  // FEM/Boundary conditions
  std::vector<BoundaryConstraint> boundary_constraints;
  std::vector<LineConstraint> line_constraints;
  std::vector<PointConstraint> point_constraints;
  // FEM/Loads
  std::vector<BoundaryLoad> boundary_forces;
  std::vector<BoundaryLoad> tractions;
  std::vector<LineLoad> line_forces;
  std::vector<PointLoad> point_forces;
  Tensor<1, 3> body_force; ///< N/m^3
  // FEM/Solver
  double solver_tolerance = 1e-10;
  unsigned int max_iterations = 2000;
  double amg_strong_threshold = 0.5;
  // FEM/Dynamics
  unsigned int n_steps = 1000;
  double time_step_factor = 0.9;
  std::string initial_displacement = "0; 0; 0";
  std::vector<Point<3>> probe_points;
  // FEM/Measurements
  std::string deflection_name = "midspan_deflection";
  std::vector<Point<3>> deflection_points;
  Tensor<1, 3> deflection_direction;
  std::string reaction_boundary;
  Tensor<1, 3> reaction_direction;
  std::string loaded_boundary;
  std::vector<std::string> reaction_boundaries;
  std::vector<PointGroup> point_groups;
  int stress_layer_axis = -1; ///< -1: no layer averages
  std::vector<double> stress_layer_edges;
  // FEM/Output
  bool write_vtu = true;
  std::string base_name = "fem";
  unsigned int output_every = 0;
};

/// Declare every FEM subsection with defaults, bounded patterns and documentation.
void declare_fem_parameters(dealii::ParameterHandler& prm);

/// Read the FEM subsections; throws std::runtime_error naming "Section/Key" on bad input.
Parameters parse_parameters(const dealii::ParameterHandler& prm);

/// "x,y,z" -> point; throws std::runtime_error mentioning @p where on bad input.
Point<3> parse_point(const std::string& text, const std::string& where);

} // namespace dembridge::fem
