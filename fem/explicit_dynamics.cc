// dembridge::fem — explicit elastodynamics (lumped mass, central differences).
#include "explicit_dynamics.h"

#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <stdexcept>

namespace dembridge::fem
{
using namespace dealii;

ExplicitDynamics::ExplicitDynamics(const Parameters& parameters, MPI_Comm comm)
    : ElasticProblem(parameters, comm)
{
}

void ExplicitDynamics::setup()
{
  make_grid();
  setup_system();
  assemble_system(/*condense=*/false);
  for (auto* v : {&mass, &inverse_mass, &u_owned, &velocity_half, &internal_force, &applied_force,
                  &acceleration})
    v->reinit(locally_owned_dofs, mpi_communicator);
  assemble_lumped_mass();
  compute_stable_time_step();
  apply_initial_displacement();
}

// M_ii = sum_q rho phi_i(x_q)^2 w_q with Gauss-Lobatto points at the nodes of FE_Q (exact
// diagonal for degree 1 and 2, whose nodes are the Gauss-Lobatto points).
void ExplicitDynamics::assemble_lumped_mass()
{
  TimerOutput::Scope t(computing_timer, "assemble mass");
  const QGaussLobatto<3> quadrature(fe.degree + 1);
  FEValues<3> fe_values(mapping, fe, quadrature, update_values | update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  std::vector<types::global_dof_index> dofs(n);
  Vector<double> cell_mass(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      cell_mass = 0;
      for (const unsigned int q : fe_values.quadrature_point_indices())
        for (unsigned int i = 0; i < n; ++i)
          cell_mass(i) += prm.density * fe_values.shape_value(i, q) * fe_values.shape_value(i, q) *
                          fe_values.JxW(q);
      cell->get_dof_indices(dofs);
      mass.add(dofs, cell_mass);
    }
  mass.compress(VectorOperation::add);
  for (const auto i : locally_owned_dofs)
  {
    if (!(mass(i) > 0))
      throw std::runtime_error("FEM/Material/density: non-positive lumped mass");
    inverse_mass(i) = 1.0 / mass(i);
  }
  inverse_mass.compress(VectorOperation::insert);
}

// Gershgorin: every eigenvalue of M^-1 K lies below max_i sum_j |K_ij| / M_ii; rows of fixed
// DoFs do not move and are left out.
void ExplicitDynamics::compute_stable_time_step()
{
  double omega2 = 0;
  for (const auto row : locally_owned_dofs)
  {
    if (constraints.is_constrained(row))
      continue;
    double sum = 0;
    for (auto entry = system_matrix.begin(row); entry != system_matrix.end(row); ++entry)
      sum += std::abs(entry->value());
    omega2 = std::max(omega2, sum / mass(row));
  }
  omega2 = Utilities::MPI::max(omega2, mpi_communicator);
  critical_time_step = 2.0 / std::sqrt(omega2);
}

void ExplicitDynamics::apply_initial_displacement()
{
  FunctionParser<3> initial(3);
  try
  {
    initial.initialize("x,y,z", prm.initial_displacement, {{"pi", numbers::PI}});
  }
  catch (const std::exception&)
  {
    throw std::runtime_error("FEM/Dynamics/initial displacement: cannot parse '" +
                             prm.initial_displacement + "'");
  }
  VectorTools::interpolate(mapping, dof_handler, initial, u_owned);
  constraints.distribute(u_owned);
  solution = u_owned;
  velocity_half = 0;
}

void ExplicitDynamics::step(const double dt)
{
  TimerOutput::Scope t(computing_timer, "explicit step");
  // a_n = M^-1 (f_ext + f_c - K u_n), zero on fixed DoFs.
  system_matrix.vmult(internal_force, u_owned);
  acceleration = external_force;
  acceleration += applied_force;
  acceleration -= internal_force;
  acceleration.scale(inverse_mass);
  constraints.set_zero(acceleration);

  // v_{n-1/2} and v_{n+1/2}; the first step starts from v_0 with half steps either side.
  LA::MPI::Vector v_minus(velocity_half);
  if (step_number == 0)
    v_minus.add(-0.5 * dt, acceleration);
  LA::MPI::Vector v_plus(v_minus);
  v_plus.add(dt, acceleration);

  // Energies at step n (before the position update).
  LA::MPI::Vector m_v(v_plus);
  m_v.scale(mass);
  energy.kinetic_shadow = 0.5 * (v_minus * m_v);
  LA::MPI::Vector v_mean(v_minus);
  v_mean += v_plus;
  v_mean *= 0.5;
  LA::MPI::Vector m_v_mean(v_mean);
  m_v_mean.scale(mass);
  energy.kinetic = 0.5 * (v_mean * m_v_mean);
  energy.strain = 0.5 * (u_owned * internal_force);
  energy.load_potential = -(external_force * u_owned);

  // u_{n+1} = u_n + dt v_{n+1/2}
  velocity_half = v_plus;
  u_owned.add(dt, velocity_half);
  constraints.distribute(u_owned);
  solution = u_owned;
  current_time += dt;
  ++step_number;
}
} // namespace dembridge::fem
