// dembridge::fem — explicit elastodynamics: lumped mass, central differences, stepped from
// outside (the coupled DEM-FE loop drives it step by step).
//
//   M a_n = f_ext + f_c - K u_n            (f_c: forces from outside, e.g. the coupling)
//   v_{n+1/2} = v_{n-1/2} + dt a_n,        v_{1/2} = v_0 + dt/2 a_0 (first step)
//   u_{n+1}   = u_n + dt v_{n+1/2}
// M is diagonal: FE_Q with Gauss-Lobatto quadrature collocated at the nodes (step-48), so
// M_ii = int rho phi_i^2 dx and the off-diagonal terms vanish. Stable for dt < 2 / omega_max;
// omega_max^2 is bounded by Gershgorin's theorem, max_i sum_j |K_ij| / M_ii.
//
// Energy: for a linear system central differences conserve exactly (to round-off) the shadow
// energy  H_n = 1/2 v_{n-1/2} . M v_{n+1/2} + 1/2 u_n . K u_n - f_ext . u_n ; the usual energy
// with v_n = (v_{n-1/2} + v_{n+1/2}) / 2 oscillates by O((omega dt)^2) around it.
#pragma once

#include "elastic_problem.h"

namespace dembridge::fem
{
class ExplicitDynamics : public ElasticProblem
{
public:
  ExplicitDynamics(const Parameters& parameters, MPI_Comm comm);

  /// make_grid, setup_system, assemble K (unconstrained) and M, initial displacement.
  void setup();
  /// 2 / omega_max from the Gershgorin bound (s); the step is factor * this value.
  double stable_time_step() const { return critical_time_step; }
  /// One central-difference step of size dt.
  void step(double dt);

  double time() const { return current_time; }
  unsigned int n_steps_done() const { return step_number; }
  /// Displacement u_n (ghosted), velocity v_{n-1/2} (owned), lumped mass diagonal (owned).
  const LA::MPI::Vector& displacement() const { return solution; }
  const LA::MPI::Vector& velocity() const { return velocity_half; }
  const LA::MPI::Vector& lumped_mass() const { return mass; }
  /// Internal nodal forces K u_n of the last step (owned).
  const LA::MPI::Vector& internal_forces() const { return internal_force; }
  /// Forces added to f_ext at every step (set by the caller, e.g. coupling forces; owned).
  LA::MPI::Vector& applied_forces() { return applied_force; }
  const dealii::DoFHandler<3>& get_dof_handler() const { return dof_handler; }

  /// Energies at the last completed step n (J); see the file comment.
  struct Energies
  {
    double kinetic_shadow = 0; ///< 1/2 v_{n-1/2} . M v_{n+1/2}
    double kinetic = 0;        ///< 1/2 v_n . M v_n, v_n the mean of the half steps
    double strain = 0;         ///< 1/2 u_n . K u_n
    double load_potential = 0; ///< -f_ext . u_n
    double shadow_total() const { return kinetic_shadow + strain + load_potential; }
    double total() const { return kinetic + strain + load_potential; }
  };
  const Energies& energies() const { return energy; }

private:
  void assemble_lumped_mass();
  void compute_stable_time_step();
  void apply_initial_displacement();

  LA::MPI::Vector mass, inverse_mass;
  LA::MPI::Vector u_owned, velocity_half, internal_force, applied_force, acceleration;
  double critical_time_step = 0;
  double current_time = 0;
  unsigned int step_number = 0;
  Energies energy;
};
} // namespace dembridge::fem
