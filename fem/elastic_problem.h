// dembridge::fem — the linear elastic continuum shared by the static and explicit solvers.
//
// Weak form (small strains, Hooke's law sigma = C : eps(u)): find u with u = g on Gamma_D and
//   a(u, v) = int_Omega eps(v) : C : eps(u) dx
//           = int_Omega v . b dx + int_Gamma_N v . t ds + sum_lines/points v . F     for all v.
// Discretisation: vector FE_Q(degree) on a parallel::distributed::Triangulation (p4est), PETSc
// matrices and vectors (step-8 + step-40). Dirichlet data on named faces (interpolated), on
// support lines and points (all nodes on them); loads as tractions, total forces spread over a
// face, consistent line forces along mesh edges and nodal point forces.
#pragma once

#include "mesh.h"
#include "parameters.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/generic_linear_algebra.h>

#include <filesystem>
#include <functional>
#include <utility>
#include <vector>

namespace dembridge::fem
{
namespace LA = dealii::LinearAlgebraPETSc;

/// A point at which a vector field is evaluated as sum_i u_i N_i(x_p) e_c(i); prepared once.
struct PointProbe
{
  dealii::Point<3> point;
  bool owned = false; ///< this rank evaluates it
  std::vector<dealii::types::global_dof_index> dofs;
  std::vector<dealii::Tensor<1, 3>> shape_vectors;
};

class ElasticProblem
{
public:
  ElasticProblem(const Parameters& parameters, MPI_Comm comm);
  virtual ~ElasticProblem() = default;

  /// Build and refine the mesh (FEM/Mesh).
  void make_grid();
  /// Distribute DoFs, build constraints (FEM/Boundary conditions), sparsity and vectors.
  void setup_system();
  /// Assemble the stiffness matrix and the load vector. With @p condense the constraints are
  /// eliminated (static solve); without, K is the plain stiffness (explicit dynamics, reactions).
  void assemble_system(bool condense);
  /// Solve the condensed system with CG + BoomerAMG; returns the number of iterations.
  unsigned int solve();
  /// The rigid-body modes the Dirichlet DoFs leave free ("translation x, rotation about z"),
  /// empty when the supports hold the body (rigid_body_modes.cc; collective).
  std::string free_rigid_body_modes() const;

  /// Displacement at a probe along @p direction (collective).
  double probe_value(const PointProbe& probe, const dealii::Tensor<1, 3>& direction) const;
  dealii::Tensor<1, 3> probe_vector(const PointProbe& probe) const;
  /// Locate @p point in the mesh; @p where names the parameter for the error message.
  PointProbe make_probe(const dealii::Point<3>& point, const std::string& where) const;

  /// Reaction force on a Dirichlet boundary: sum over its DoFs of f_int - f_ext (collective).
  dealii::Tensor<1, 3> reaction(dealii::types::boundary_id id) const;
  /// Area, centroid and mean displacement of a boundary (collective).
  struct BoundaryMeans
  {
    double area = 0;
    dealii::Point<3> centroid;
    dealii::Tensor<1, 3> mean_displacement;
  };
  BoundaryMeans boundary_means(dealii::types::boundary_id id) const;
  /// Strain energy 1/2 int eps : C : eps dx of the current solution (collective).
  double strain_energy() const;
  /// Stress integrated over the slabs edges[k] <= x[axis] < edges[k+1] of the body: volume of
  /// the body in each slab and the mean stress there (collective). Quadrature points (2x2x2
  /// copies of the Gauss rule per cell) are assigned by position: exact when the edges lie on
  /// cell faces.
  struct LayerStresses
  {
    std::vector<double> volume;
    std::vector<dealii::SymmetricTensor<2, 3>> sigma; ///< Pa, int sigma dx / volume
  };
  LayerStresses layer_stresses(unsigned int axis, const std::vector<double>& edges) const;
  /// Write displacement, strain, stress and von Mises stress (.vtu per rank, .pvtu, .pvd), and
  /// the cell fields added by add_cell_output.
  void output_results(const std::filesystem::path& output_dir, unsigned int cycle, double time);
  /// A cell field written with the next outputs: @p value at each cell's centre.
  void add_cell_output(const std::string& name,
                       std::function<double(const dealii::Point<3>&)> value)
  {
    cell_outputs.emplace_back(name, std::move(value));
  }

  dealii::types::global_dof_index n_dofs() const { return dof_handler.n_dofs(); }
  dealii::types::global_cell_index n_cells() const { return triangulation.n_global_active_cells(); }
  const BoundaryNames& boundary_names() const { return names; }
  dealii::TimerOutput& timer() { return computing_timer; }
  /// The snapshots written so far (time, .pvtu name): the .pvd's records.
  const std::vector<std::pair<double, std::string>>& snapshot_records() const
  {
    return pvtu_records;
  }

protected:
  /// Internal nodal forces f_int = int B^T sigma(u) dx, unconstrained (ghosted input).
  void compute_internal_forces(const LA::MPI::Vector& u, LA::MPI::Vector& f_int) const;

  void make_constraints();
  void
  assemble_line_forces(std::vector<std::pair<dealii::types::global_dof_index, double>>& f) const;
  void
  assemble_point_forces(std::vector<std::pair<dealii::types::global_dof_index, double>>& f) const;
  /// Distance from @p x to the segment [a, b].
  static double distance_to_segment(const dealii::Point<3>& x, const dealii::Point<3>& a,
                                    const dealii::Point<3>& b);

  const Parameters prm;
  MPI_Comm mpi_communicator;
  dealii::ConditionalOStream pcout;
  mutable dealii::TimerOutput computing_timer;

  dealii::parallel::distributed::Triangulation<3> triangulation;
  BoundaryNames names;
  dealii::FESystem<3> fe;
  dealii::MappingQ1<3> mapping;
  dealii::DoFHandler<3> dof_handler;
  dealii::SymmetricTensor<4, 3> stiffness;
  /// Weight of the stiffness at a point, C -> w(x) C in the assembly (a coupled run's 1 - alpha
  /// in the handshake band, coupling/); empty: 1 everywhere.
  std::function<double(const dealii::Point<3>&)> stiffness_weight;
  /// Called with every cell's DoFs and element matrix by an unconstrained assembly (the
  /// explicit step's cell-by-cell operator, element_operator.h).
  std::function<void(const std::vector<dealii::types::global_dof_index>&,
                     const dealii::FullMatrix<double>&)>
      cell_matrix_sink;
  double geometric_tolerance = 0;

  dealii::IndexSet locally_owned_dofs;
  dealii::IndexSet locally_relevant_dofs;
  dealii::AffineConstraints<double> constraints;

  LA::MPI::SparseMatrix system_matrix;
  LA::MPI::Vector system_rhs;     ///< condensed right-hand side (static solve)
  LA::MPI::Vector external_force; ///< unconstrained nodal external forces
  LA::MPI::Vector solution;       ///< ghosted displacement

  std::vector<std::pair<double, std::string>> pvtu_records;
  std::vector<std::pair<std::string, std::function<double(const dealii::Point<3>&)>>> cell_outputs;
};

} // namespace dembridge::fem
