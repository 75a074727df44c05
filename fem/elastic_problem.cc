// dembridge::fem — the linear elastic continuum: mesh, DoFs, constraints, assembly, solve.
#include "elastic_problem.h"
#include "fem/incompatible_modes.h"

#include "material.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace dembridge::fem
{
using namespace dealii;

ElasticProblem::ElasticProblem(const Parameters& parameters, MPI_Comm comm)
    : prm(parameters), mpi_communicator(comm),
      pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0),
      // Timer without communicator: an MPI TimerOutput prints a multi-line notice when an input
      // error unwinds through it; statistics over ranks come from print_wall_time_statistics.
      computing_timer(pcout, TimerOutput::never, TimerOutput::wall_times), triangulation(comm),
      fe(FE_Q<3>(parameters.degree), 3), dof_handler(triangulation),
      stiffness(stiffness_tensor(parameters))
{
}

double ElasticProblem::distance_to_segment(const Point<3>& x, const Point<3>& a, const Point<3>& b)
{
  const Tensor<1, 3> ab = b - a;
  const double length2 = ab.norm_square();
  const double s = length2 > 0 ? std::clamp((x - a) * ab / length2, 0.0, 1.0) : 0.0;
  return x.distance(a + s * ab);
}

void ElasticProblem::make_grid()
{
  TimerOutput::Scope t(computing_timer, "make grid");
  names = make_mesh(prm, triangulation);
  geometric_tolerance = 1e-6 * GridTools::minimal_cell_diameter(triangulation);
}

// ------------------------------------------------------------------------------------------
// Constraints: faces (interpolated data), then support lines and points (every node on them).
// A node fixed twice keeps its first constraint.
void ElasticProblem::make_constraints()
{
  constraints.clear();
  constraints.reinit(locally_relevant_dofs);
  DoFTools::make_hanging_node_constraints(dof_handler, constraints);

  for (const auto& c : prm.boundary_constraints)
  {
    const std::string where = "FEM/Boundary conditions/boundaries";
    const types::boundary_id id = find_boundary(names, c.boundary, where);
    unsigned int n_faces = 0;
    for (const auto& cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto& face : cell->face_iterators())
          n_faces += face->at_boundary() && face->boundary_id() == id;
    if (Utilities::MPI::sum(n_faces, mpi_communicator) == 0)
      throw std::runtime_error(where + ": boundary '" + c.boundary + "' has no faces");
    const ComponentMask mask(std::vector<bool>(c.components.begin(), c.components.end()));
    VectorTools::interpolate_boundary_values(
        mapping, dof_handler, id, Functions::ConstantFunction<3>(c.value, 3), constraints, mask);
  }

  // Support lines and points: every node (support point) of a non-artificial cell that lies on
  // the line or at the point is fixed in the listed components; all ranks see the same nodes.
  const auto fix_nodes = [&](const auto& on_support, const ComponentSet& components,
                             const std::string& where, const std::string& what)
  {
    const auto& unit_points = fe.get_unit_support_points();
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    unsigned int n_found = 0;
    for (const auto& cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
        {
          const unsigned int component = fe.system_to_component_index(i).first;
          const Point<3> x = mapping.transform_unit_to_real_cell(cell, unit_points[i]);
          if (!on_support(x))
            continue;
          n_found += cell->is_locally_owned();
          if (components[component] && locally_relevant_dofs.is_element(dofs[i]) &&
              !constraints.is_constrained(dofs[i]))
            constraints.add_line(dofs[i]);
        }
      }
    if (Utilities::MPI::sum(n_found, mpi_communicator) == 0)
      throw std::runtime_error(where + ": no mesh node on " + what);
  };
  for (const auto& c : prm.line_constraints)
    fix_nodes([&](const Point<3>& x)
              { return distance_to_segment(x, c.a, c.b) < geometric_tolerance; },
              c.components, "FEM/Boundary conditions/lines", "the segment");
  for (const auto& c : prm.point_constraints)
    fix_nodes([&](const Point<3>& x) { return x.distance(c.p) < geometric_tolerance; },
              c.components, "FEM/Boundary conditions/points", "the point");
  constraints.close();
}

void ElasticProblem::setup_system()
{
  TimerOutput::Scope t(computing_timer, "setup system");
  dof_handler.distribute_dofs(fe);
  locally_owned_dofs = dof_handler.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);
  make_constraints();

  DynamicSparsityPattern dsp(locally_relevant_dofs);
  DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, /*keep_constrained_dofs=*/true);
  SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs, mpi_communicator,
                                             locally_relevant_dofs);
  system_matrix.reinit(locally_owned_dofs, locally_owned_dofs, dsp, mpi_communicator);
  system_rhs.reinit(locally_owned_dofs, mpi_communicator);
  external_force.reinit(locally_owned_dofs, mpi_communicator);
  solution.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
}

// ------------------------------------------------------------------------------------------
// Line forces: F / |b - a| per unit length along every mesh edge on the segment, integrated
// with the shape functions of each cell that holds the edge (consistent nodal forces). An edge
// shared by k cells is integrated by each with weight 1/k, so that the sum over ranks is exact.
void ElasticProblem::assemble_line_forces(
    std::vector<std::pair<types::global_dof_index, double>>& f) const
{
  const QGauss<1> gauss(prm.degree + 1);
  std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
  for (const auto& load : prm.line_forces)
  {
    const double length = load.a.distance(load.b);
    const auto on_segment = [&](const auto& line)
    {
      return distance_to_segment(line->vertex(0), load.a, load.b) < geometric_tolerance &&
             distance_to_segment(line->vertex(1), load.a, load.b) < geometric_tolerance;
    };
    std::map<unsigned int, unsigned int> cells_per_line;
    for (const auto& cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (unsigned int l = 0; l < GeometryInfo<3>::lines_per_cell; ++l)
          if (on_segment(cell->line(l)))
            ++cells_per_line[cell->line(l)->index()];

    double covered = 0;
    for (const auto& cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int l = 0; l < GeometryInfo<3>::lines_per_cell; ++l)
          if (on_segment(cell->line(l)))
          {
            const double weight = 1.0 / cells_per_line[cell->line(l)->index()];
            const double edge = cell->line(l)->vertex(0).distance(cell->line(l)->vertex(1));
            covered += weight * edge;
            const Point<3> v0 =
                GeometryInfo<3>::unit_cell_vertex(GeometryInfo<3>::line_to_cell_vertices(l, 0));
            const Point<3> v1 =
                GeometryInfo<3>::unit_cell_vertex(GeometryInfo<3>::line_to_cell_vertices(l, 1));
            std::vector<Point<3>> points;
            std::vector<double> weights;
            for (unsigned int q = 0; q < gauss.size(); ++q)
            {
              points.push_back(v0 + gauss.point(q)[0] * (v1 - v0));
              weights.push_back(gauss.weight(q));
            }
            FEValues<3> fe_values(mapping, fe, Quadrature<3>(points, weights), update_values);
            fe_values.reinit(cell);
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              const unsigned int c = fe.system_to_component_index(i).first;
              double value = 0;
              for (unsigned int q = 0; q < points.size(); ++q)
                value += fe_values.shape_value(i, q) * weights[q] * edge; // ds = edge * dw
              if (value != 0)
                f.emplace_back(dofs[i], weight * value * load.force[c] / length);
            }
          }
    covered = Utilities::MPI::sum(covered, mpi_communicator);
    if (covered == 0)
      throw std::runtime_error("FEM/Loads/line forces: the segment lies on no mesh edge "
                               "(empty load line)");
    if (std::abs(covered - length) > 1e-6 * length)
      throw std::runtime_error("FEM/Loads/line forces: mesh edges cover " +
                               std::to_string(covered) + " m of the " + std::to_string(length) +
                               " m segment");
  }
}

// Point forces go to the three DoFs of the node nearest to the point.
void ElasticProblem::assemble_point_forces(
    std::vector<std::pair<types::global_dof_index, double>>& f) const
{
  const auto& unit_points = fe.get_unit_support_points();
  std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
  const double max_diameter = GridTools::maximal_cell_diameter(triangulation);
  for (const auto& load : prm.point_forces)
  {
    double nearest = std::numeric_limits<double>::max();
    Point<3> node;
    for (const auto& cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int v = 0; v < GeometryInfo<3>::vertices_per_cell; ++v)
          if (cell->vertex(v).distance(load.p) < nearest)
          {
            nearest = cell->vertex(v).distance(load.p);
            node = cell->vertex(v);
          }
    const double global_nearest = Utilities::MPI::min(nearest, mpi_communicator);
    if (global_nearest > max_diameter)
      throw std::runtime_error("FEM/Loads/point forces: the point lies outside the mesh");
    const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
    const unsigned int winner = Utilities::MPI::min(
        nearest == global_nearest ? rank : std::numeric_limits<unsigned int>::max(),
        mpi_communicator);
    if (rank != winner)
      continue;
    std::set<types::global_dof_index> done;
    for (const auto& cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          if (mapping.transform_unit_to_real_cell(cell, unit_points[i]).distance(node) <
                  geometric_tolerance &&
              done.insert(dofs[i]).second)
            f.emplace_back(dofs[i], load.force[fe.system_to_component_index(i).first]);
      }
  }
}

// ------------------------------------------------------------------------------------------
// Assembly (step-8): A_ij = int eps(phi_i) : C : eps(phi_j) dx,
//                    f_i  = int phi_i . b dx + int_Gamma_N phi_i . t ds + nodal line/point forces.
void ElasticProblem::assemble_system(const bool condense)
{
  TimerOutput::Scope t(computing_timer, "assemble system");
  system_matrix = 0;
  system_rhs = 0;
  external_force = 0;

  // Tractions per boundary id: given directly, or a total force divided by the face area.
  std::map<types::boundary_id, Tensor<1, 3>> traction;
  for (const auto& load : prm.tractions)
    traction[find_boundary(names, load.boundary, "FEM/Loads/tractions")] += load.vector;
  for (const auto& load : prm.boundary_forces)
  {
    const auto id = find_boundary(names, load.boundary, "FEM/Loads/boundary forces");
    const double area = boundary_means(id).area;
    if (!(area > 0))
      throw std::runtime_error("FEM/Loads/boundary forces: boundary '" + load.boundary +
                               "' has no faces (empty load boundary)");
    traction[id] += load.vector / area;
  }
  for (const auto& load : prm.tractions)
    if (!(boundary_means(find_boundary(names, load.boundary, "")).area > 0))
      throw std::runtime_error("FEM/Loads/tractions: boundary '" + load.boundary +
                               "' has no faces (empty load boundary)");

  const QGauss<3> quadrature(fe.degree + 1);
  const QGauss<2> face_quadrature(fe.degree + 1);
  FEValues<3> fe_values(mapping, fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  FEFaceValues<3> fe_face_values(mapping, fe, face_quadrature, update_values | update_JxW_values);
  // incompatible modes: the Jacobian at the cell centre (incompatible_modes.h)
  const QMidpoint<3> centre;
  FEValues<3> centre_values(mapping, fe, centre, update_inverse_jacobians | update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  FullMatrix<double> cell_matrix(n, n);
  Vector<double> cell_rhs(n);
  std::vector<types::global_dof_index> dofs(n);
  std::vector<SymmetricTensor<2, 3>> eps(n);

  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      cell_matrix = 0;
      cell_rhs = 0;
      fe_values.reinit(cell);
      for (const unsigned int q : fe_values.quadrature_point_indices())
      {
        for (unsigned int i = 0; i < n; ++i)
        {
          const unsigned int c = fe.system_to_component_index(i).first;
          Tensor<1, 3> e;
          e[c] = 1;
          eps[i] = symmetrize(outer_product(e, fe_values.shape_grad(i, q)));
        }
        const double w = stiffness_weight ? stiffness_weight(fe_values.quadrature_point(q)) : 1.0;
        for (unsigned int i = 0; i < n; ++i)
        {
          const SymmetricTensor<2, 3> C_eps_i = stiffness * eps[i];
          for (unsigned int j = 0; j < n; ++j)
            cell_matrix(i, j) += w * (C_eps_i * eps[j]) * fe_values.JxW(q);
          cell_rhs(i) += fe_values.shape_value(i, q) *
                         prm.body_force[fe.system_to_component_index(i).first] * fe_values.JxW(q);
        }
      }
      if (prm.incompatible_modes)
      {
        centre_values.reinit(cell);
        condense_incompatible_modes(fe_values, stiffness, stiffness_weight, prm.body_force,
                                    centre_values.inverse_jacobian(0), centre_values.JxW(0),
                                    cell_matrix, cell_rhs);
      }
      for (const auto& face : cell->face_iterators())
        if (face->at_boundary() && traction.count(face->boundary_id()))
        {
          const Tensor<1, 3> t_face = traction[face->boundary_id()];
          fe_face_values.reinit(cell, face);
          for (const unsigned int q : fe_face_values.quadrature_point_indices())
            for (unsigned int i = 0; i < n; ++i)
              cell_rhs(i) += fe_face_values.shape_value(i, q) *
                             t_face[fe.system_to_component_index(i).first] * fe_face_values.JxW(q);
        }
      cell->get_dof_indices(dofs);
      external_force.add(dofs, cell_rhs);
      if (condense)
        constraints.distribute_local_to_global(cell_matrix, cell_rhs, dofs, system_matrix,
                                               system_rhs);
      else
      {
        system_matrix.add(dofs, cell_matrix);
        if (cell_matrix_sink)
          cell_matrix_sink(dofs, cell_matrix);
      }
    }

  std::vector<std::pair<types::global_dof_index, double>> nodal;
  assemble_line_forces(nodal);
  assemble_point_forces(nodal);
  for (const auto& [dof, value] : nodal)
  {
    const std::vector<types::global_dof_index> one{dof};
    Vector<double> value_vector(1);
    value_vector(0) = value;
    external_force.add(one, value_vector);
    if (condense)
      constraints.distribute_local_to_global(value_vector, one, system_rhs);
  }
  system_matrix.compress(VectorOperation::add);
  system_rhs.compress(VectorOperation::add);
  external_force.compress(VectorOperation::add);
}

// ------------------------------------------------------------------------------------------
// Solve (step-40): CG preconditioned by PETSc's BoomerAMG; 3D elasticity wants a strong threshold
// of about 0.5 (hypre's advice for 3D problems) and a symmetric (V-cycle, symmetric smoother)
// setup.
unsigned int ElasticProblem::solve()
{
  TimerOutput::Scope t(computing_timer, "solve");
  LA::MPI::Vector distributed(locally_owned_dofs, mpi_communicator);
  const double rhs_norm = system_rhs.l2_norm();
  unsigned int iterations = 0;
  if (rhs_norm > 0)
  {
    SolverControl control(prm.max_iterations, prm.solver_tolerance * rhs_norm);
    // deal.II's CG measures the true residual |b - Ax| (PETSc's KSPCG would test the
    // preconditioned one, whose scale differs from |b| by the order of 1/E).
    SolverCG<LA::MPI::Vector> cg(control);
    LA::MPI::PreconditionAMG amg;
    LA::MPI::PreconditionAMG::AdditionalData data;
    data.symmetric_operator = true;
    data.strong_threshold = prm.amg_strong_threshold;
    // Systems AMG ("unknown approach"): PETSc hands hypre the matrix block size as the number
    // of functions, so that only couplings within one displacement component count as strong.
    // deal.II numbers the three components of a node consecutively.
    {
      const PetscErrorCode ierr = MatSetBlockSize(static_cast<Mat>(system_matrix), 3);
      if (ierr != 0)
        pcout << "FEM: could not set the matrix block size (PETSc error " << ierr << ")"
              << std::endl;
    }
    {
      TimerOutput::Scope amg_timer(computing_timer, "amg setup"); // part of "solve"
      amg.initialize(system_matrix, data);
    }
    try
    {
      cg.solve(system_matrix, distributed, system_rhs, amg);
    }
    catch (const SolverControl::NoConvergence& e)
    {
      throw std::runtime_error("FEM/Solver/max iterations: CG did not converge in " +
                               std::to_string(e.last_step) + " iterations (residual " +
                               std::to_string(e.last_residual) + ")");
    }
    iterations = control.last_step();
  }
  constraints.distribute(distributed);
  solution = distributed;
  return iterations;
}

} // namespace dembridge::fem
