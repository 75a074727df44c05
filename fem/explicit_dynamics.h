// dembridge::fem — explicit elastodynamics: lumped mass, central differences, stepped from
// outside phase by phase (the coupled DEM-FE loop, coupling/, inserts its forces between them).
//
//   M a_n = f_ext + f_c - K u_n - c M v_{n-1/2}   (f_c: forces from outside, e.g. the coupling;
//                                                 c: mass-proportional damping, 1/s, lagged)
//   v_{n+1/2} = v_{n-1/2} + dt a_n,   u_{n+1} = u_n + dt v_{n+1/2}
// Start: by default the given initial velocity is v_0 at t_0 and the first step takes
// v_{1/2} = v_0 + dt/2 a_0; with set_half_step_start(false) it is read as v_{-1/2}, the DEM
// solver's convention (dem/solvers/explicit_solver.h), so that a coupled run starts both sides
// alike.
// M is diagonal: FE_Q with Gauss-Lobatto quadrature collocated at the nodes (step-48), so
// M_ii = int w_M rho phi_i^2 dx and the off-diagonal terms vanish. Coupled runs weight the
// density by w_M(x) and the stiffness by w_K(x) at the quadrature points (the handshake band's
// 1 - alpha, coupling/handshake.h); both are 1 otherwise. Stable for dt < 2 / omega_max;
// omega_max^2 is bounded by Gershgorin's theorem, max_i sum_j |K_ij| / M_ii, and for FE_Q1 by
// the element eigenvalue inequality (element_operator.h), whichever is smaller. K u_n is
// applied cell by cell for FE_Q1 (element_operator.h), by the assembled matrix otherwise.
//
// One step, three phases:
//   predict(dt)        f^n = f_ext - K u_n - c M v_{n-1/2};  trial  v^ = v_{n-1/2} + dt M^-1 f^n
//   apply_force(f, dt) v^ += dt M^-1 f   (coupling forces; their work is booked)
//   update(dt)         v_{n+1/2} = v^ (prescribed DoFs: (g(t_{n+1}) - u_n) / dt),
//                      u_{n+1} = u_n + dt v_{n+1/2}, energies of step n
// step(dt) runs the three with no outside force. No vector is allocated per step.
//
// Energy: for a linear system central differences conserve exactly (to round-off) the shadow
// energy  H_n = 1/2 v_{n-1/2} . M v_{n+1/2} + 1/2 u_n . K u_n - f_ext . u_n ; the usual energy
// with v_n = (v_{n-1/2} + v_{n+1/2}) / 2 oscillates by O((omega dt)^2) around it. Works of the
// damping, of outside forces and of prescribed boundary displacements are summed with the
// trapezoidal rule f^n . (v_{n-1/2} + v_{n+1/2}) / 2 dt, the form that keeps the balance
//   H_n + W_damping = H_0 + W_outside + W_boundary
// exact for a linear system.
#pragma once

#include "elastic_problem.h"
#include "element_operator.h"

#include <deal.II/base/function.h>

#include <functional>

namespace dembridge::dem
{
class StateArchive; // dem/core/state_archive.h
}

namespace dembridge::fem
{
/// Runs @p visit on rank 0 (saving) and on every other rank (restoring what rank 0's visit
/// named): rank 0's state for all (collective; the visit must name the same fields everywhere).
void broadcast_state(MPI_Comm comm, const std::function<void(dem::StateArchive&)>& visit);

class ExplicitDynamics : public ElasticProblem
{
public:
  ExplicitDynamics(const Parameters& parameters, MPI_Comm comm);

  using PointFunction = std::function<double(const dealii::Point<3>&)>;
  using GridBuilder =
      std::function<BoundaryNames(dealii::parallel::distributed::Triangulation<3>&)>;

  // ---- options, set before setup() ------------------------------------------------------
  /// Weights of the stiffness and the density at a point (coupled runs); default 1.
  void set_weights(PointFunction stiffness_weight_function, PointFunction mass_weight_function);
  /// Builds the mesh instead of FEM/Mesh (coupled runs cut the particle-only region out).
  void set_grid_builder(GridBuilder builder) { grid_builder = std::move(builder); }
  /// Mass-proportional damping coefficient c (1/s).
  void set_mass_damping(double c) { mass_damping = c; }
  /// true (default): the initial velocity is v_0 at t_0; false: it is v_{-1/2}.
  void set_half_step_start(bool half) { half_step_start = half; }

  /// make_grid (or the grid builder), setup_system, assemble K (unconstrained, weighted) and
  /// M, initial displacement (FEM/Dynamics/initial displacement).
  void setup();
  /// Replaces the initial state (after setup): u_0 = u0(x), initial velocity v0(x) at the nodes.
  void set_initial_state(const dealii::Function<3>& u0, const dealii::Function<3>& v0);
  /// Continues the time line of @p earlier, a continuum of the same run on a mesh that has lost
  /// cells since (a coupled run whose particle region grew): its time, step count and .pvd
  /// records, and @p velocity on the driven DoFs (set_initial_state holds them at rest). The
  /// works start anew from here (the caller carries their sums). After set_initial_state.
  void continue_from(const ExplicitDynamics& earlier, const dealii::Function<3>& velocity);
  /// Boundary @p id moves in the components of @p mask to u = ramp(t) g(x) (after setup):
  /// its DoFs are driven, the force they need is a reaction whose work is booked.
  void prescribe_boundary_displacement(dealii::types::boundary_id id, const ComponentSet& mask,
                                       const dealii::Function<3>& g,
                                       std::function<double(double)> ramp);

  /// 2 / omega_max from the bound below (s); the step is factor * this value.
  double stable_time_step() const { return critical_time_step; }
  /// An upper bound on omega_max^2 of M^-1 K over the DoFs that move, with @p added_mass (owned;
  /// nullptr: none) on the nodes: the smaller of Gershgorin's, max_i sum_j |K_ij| / M_ii, and
  /// the element eigenvalue inequality's (element_operator.h), both rigorous (collective).
  double frequency_bound(const LA::MPI::Vector* added_mass = nullptr) const;

  /// One central-difference step of size dt (predict, update).
  void step(double dt);
  void predict(double dt);
  void apply_force(const LA::MPI::Vector& f, double dt);
  /// With record = false only the works are summed; energies() then still hold an earlier
  /// step's values.
  void update(double dt, bool record = true);

  double time() const { return current_time; }
  unsigned int n_steps_done() const { return step_number; }
  /// Displacement u_n (ghosted), velocity v_{n-1/2} (owned), lumped mass diagonal (owned).
  const LA::MPI::Vector& displacement() const { return solution; }
  const LA::MPI::Vector& velocity() const { return velocity_half; }
  /// Trial velocity v^ between predict() and update() (owned).
  const LA::MPI::Vector& trial_velocity() const { return velocity_trial; }
  const LA::MPI::Vector& lumped_mass() const { return mass; }
  /// The lumped mass without the density weight (owned): the coupling shares the band's mass
  /// between the two sides by the ratio of the two.
  const LA::MPI::Vector& lumped_mass_unweighted() const { return mass_unweighted; }
  /// M^-1 with zeros on fixed and driven DoFs (they do not answer forces) (owned).
  const LA::MPI::Vector& inverse_lumped_mass() const { return inverse_mass; }
  /// Internal nodal forces K u_n of the last step (owned).
  const LA::MPI::Vector& internal_forces() const { return internal_force; }
  /// Forces added to f_ext at every step (set by the caller; owned).
  LA::MPI::Vector& applied_forces() { return applied_force; }

  const dealii::DoFHandler<3>& get_dof_handler() const { return dof_handler; }
  const dealii::Mapping<3>& get_mapping() const { return mapping; }
  const dealii::FESystem<3>& get_fe() const { return fe; }
  const dealii::IndexSet& owned_dofs() const { return locally_owned_dofs; }
  const dealii::IndexSet& relevant_dofs() const { return locally_relevant_dofs; }
  MPI_Comm communicator() const { return mpi_communicator; }
  const dealii::parallel::distributed::Triangulation<3>& get_triangulation() const
  {
    return triangulation;
  }
  const dealii::AffineConstraints<double>& get_constraints() const { return constraints; }
  /// The assembled (weighted, unconstrained) stiffness matrix and its cell-by-cell form.
  const LA::MPI::SparseMatrix& stiffness_matrix() const { return system_matrix; }
  const ElementOperator& element_operator() const { return cell_operator; }

  /// Of the current state, between steps (collective, J): the strain energy 1/2 u.K u with the
  /// weighted K, the load potential -f_ext.u, and 1/2 v.M v with the weighted lumped M and the
  /// velocity v_{n-1/2}.
  struct EnergiesNow
  {
    double strain = 0, load_potential = 0, kinetic = 0;
  };
  EnergiesNow energies_now() const;

  /// Energies at the last completed step n (J); see the file comment.
  struct Energies
  {
    double kinetic_shadow = 0; ///< 1/2 v_{n-1/2} . M v_{n+1/2}
    double kinetic = 0;        ///< 1/2 v_n . M v_n, v_n the mean of the half steps
    double strain = 0;         ///< 1/2 u_n . K u_n
    double load_potential = 0; ///< -f_ext . u_n
    double damping = 0;        ///< work dissipated by the mass damping up to t_n
    double outside_work = 0;   ///< work of apply_force() and applied_forces() up to t_n
    double boundary_work = 0;  ///< work of the prescribed boundary displacements up to t_n
    double shadow_total() const { return kinetic_shadow + strain + load_potential; }
    double total() const { return kinetic + strain + load_potential; }
  };
  const Energies& energies() const { return energy; }

  /// Checkpoints (docs/checkpoint.md, group /fe/) on any number of MPI ranks, with rank 0 alone
  /// at the file: what a step reads from the previous ones, u_n, v_{n-1/2}, the applied forces
  /// (in global DoF order, checked against this mesh's DoF count on restore), the works summed
  /// so far (one value per rank: each rank sums its own share), time and step count, the last
  /// energies and the .pvd records.
  ///  - saving: gather_state() (collective) brings every rank's part to rank 0, whose
  ///    visit_state(a) writes it;
  ///  - restoring: rank 0's visit_state(a) reads it (refusing another DoF or rank count), then
  ///    scatter_state() (collective) gives every rank its owned entries, its works and rank 0's
  ///    time, steps, energies and records.
  void gather_state();
  void visit_state(dem::StateArchive& a);
  void scatter_state();

  /// Writes displacement, strain, stress (.vtu per rank, .pvtu, FEM/Output/base name .pvd);
  /// returns the .pvtu file name (relative to @p output_dir).
  std::string output(const std::filesystem::path& output_dir, unsigned int cycle, double time);

private:
  /// Time, steps, energies and .pvd records: the same on every rank.
  void visit_scalars(dem::StateArchive& a);
  /// Every rank's owned range (PETSc owns one contiguous range per rank, in rank order).
  void owned_ranges(std::vector<int>& counts, std::vector<int>& offsets) const;

  void assemble_lumped_mass();
  void compute_stable_time_step();
  void apply_initial_displacement();

  GridBuilder grid_builder;
  PointFunction mass_weight;
  double mass_damping = 0;
  bool half_step_start = true;
  bool has_hanging_nodes = false;

  /// K u cell by cell (FE_Q1; otherwise the assembled matrix is used)
  ElementOperator cell_operator;
  LA::MPI::Vector mass, mass_unweighted, inverse_mass, row_sums;
  LA::MPI::Vector u_owned, velocity_half, velocity_trial, internal_force, applied_force, step_force,
      outside_force;
  bool outside_force_applied = false;

  /// Driven DoFs: owned local index, target g_i and ramp r; u_i(t) = r(t) g_i.
  struct DrivenDof
  {
    unsigned int local;
    double target;
    unsigned int ramp;
  };
  std::vector<DrivenDof> driven;
  std::vector<std::function<double(double)>> drive_ramps;

  /// The works as summed step by step (trapezoidal, with the half-step lead, see update()):
  /// this rank's shares.
  double boundary_work_summed = 0, damping_summed = 0, outside_work_summed = 0;
  /// The state of a checkpoint on rank 0 between gather/visit and visit/scatter: whole vectors
  /// and the works of every rank (empty otherwise).
  struct Gathered
  {
    std::vector<double> u, v, applied, boundary_work, damping, outside_work;
  } gathered;
  double critical_time_step = 0;
  double current_time = 0;
  unsigned int step_number = 0;
  Energies energy;
};
} // namespace dembridge::fem
