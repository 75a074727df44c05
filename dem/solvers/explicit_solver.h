#pragma once
// Explicit dynamics of a bonded-particle system: position Verlet / central differences
// (thesis eq. 38-45) with bond dashpots and particle damping, supports and loads on groups,
// and the energy balance (thesis eq. 49-53).
//
// One step at time t_n (positions x^n, velocities v^{n-1/2}):
//   1. bond forces from x^n, q^n (unified law, bond_kernel.h), dashpots from v^{n-1/2};
//   2. external forces and moments of the loads at t_n (a pressure's ratio part from the
//      support reactions of step n-1);
//   3. particle damping F''_i = -gamma |F_i| sign(v_i) per component (paper eq. 11-12), and
//      mass damping -c m v^{n-1/2} (lagged: explicit, stable for c dt < 2);
//   4. v^{n+1/2} = v^{n-1/2} + dt F/m (eq. 40), w likewise with I (eq. 44); constrained DOFs
//      take their prescribed value and the force needed for that is their reaction;
//   5. x^{n+1} = x^n + dt v^{n+1/2} (eq. 41); q^{n+1} = exp(dt w^{n+1/2} / 2) q^n (the
//      quaternion form of eq. 45, exact for constant w).
// No allocation and no virtual call happen inside step(). With threads > 1 the bonds are
// grouped by particle index chunks (bond_partition.h; compact regions when the particles are in
// spatial order, renumbering.h) so that threads never write the same particle (no atomics, the
// result does not depend on the thread count beyond round-off order within a particle).
// Bond failure (bond_damage.h): with a failure law the bond loop is a separate instantiation
// that evaluates every bond's stresses on its trial forces each step, softens or breaks it (a
// bond writes only its own state), books the released energy as fracture, and logs failures in
// per-range buffers reserved up front; they are drained after the loop, in particle-id order,
// into the crack log (cracks()), and the particles' coordination numbers follow. Without a
// failure law the loop is the plain one.
#include "dem/bonds/bond_store.h"
#include "dem/core/energy.h"
#include "dem/core/particle_store.h"
#include "dem/model/groups.h"
#include "dem/model/loads.h"
#include "dem/solvers/step_contribution.h"
#include <array>
#include <limits>
#include <vector>

namespace dembridge::dem
{
struct SolverSettings
{
  double time_step = 0;        ///< s
  double particle_damping = 0; ///< gamma (paper eq. 11-12), dimensionless, in [0, 1)
  int threads = 1;
  /// c (1/s): mass-proportional damping -c m v^{n-1/2} on every particle's translation (what
  /// Coupling/mass damping applies in a coupled run, so that a full-DEM run can match it)
  double mass_damping = 0;
  /// Distributed runs (distributed/): the particles [0, owned_particles) are this rank's, the
  /// rest ghosts, copies of other ranks' particles that the caller refreshes between steps. A
  /// step integrates the owned particles only; a bond with a ghost end is held by both ranks
  /// and computed alike on both, and books its energies, failure and crack log entry on the
  /// rank that owns its end a only. The default: every particle is owned.
  std::size_t owned_particles = std::numeric_limits<std::size_t>::max();
};

class ExplicitSolver
{
public:
  ExplicitSolver(ParticleStore& particles, BondStore& bonds, std::vector<Group> groups,
                 std::vector<Constraint> constraints, std::vector<Load> loads,
                 const SolverSettings& settings);

  /// Advances one time step. With record = true, also refreshes the per-bond forces, the strain
  /// and kinetic energies and the maximum speed (kept off the hot path otherwise).
  void step(bool record = false);

  /// The bond forces of the current state, without a step: p.force / p.torque hold the bonds'
  /// particle resultants (dashpots included), dashpot_forces() / dashpot_torques() their
  /// dashpot parts, energy().strain the bonds' strain energy and bonds.force / moment each
  /// bond's contact force and couple. For tests and tools (the optimised loop against
  /// bond_kernel.h); failure laws are not applied.
  void evaluate_bond_forces();
  std::vector<Vec3> dashpot_forces() const;
  std::vector<Vec3> dashpot_torques() const;

  double time() const { return time_; }
  long steps() const { return steps_; }
  double time_step() const { return settings_.time_step; }
  const EnergyBalance& energy() const { return energy_; }
  double max_speed() const { return max_speed_; }
  /// Unbalanced-force ratio at the last record (PFC's convention): the mean magnitude of the
  /// net force on the free translational DOFs of the particles over the mean magnitude of the
  /// intact bonds' forces. It falls towards 0 only in equilibrium; unlike the largest speed it
  /// stays large at the turning point of an oscillation, where the velocities vanish but the
  /// forces do not.
  double unbalanced_force_ratio() const { return unbalanced_ratio_; }
  const std::vector<Group>& groups() const { return groups_; }
  /// Every bond failure so far, in time order (within a step by particle ids).
  const std::vector<CrackEvent>& cracks() const { return cracks_; }
  long n_broken_bonds() const { return long(cracks_.size()); }
  /// Broken bonds whose failure was governed by tension / by shear.
  long broken_bonds(CrackMode mode) const { return broken_by_mode_[int(mode)]; }
  const std::vector<Load>& loads() const { return loads_; }
  /// The stores the solver advances; bond indices are in its order (CrackEvent::bond).
  const ParticleStore& particles() const { return p_; }
  const BondStore& bonds() const { return b_; }

  /// The unbalanced-force ratio's parts at the last record (distributed runs add them over
  /// ranks): the sum of |net force| over the particles with a free translation and their
  /// count, the sum of |F_c| over the intact bonds and their count.
  struct UnbalancedParts
  {
    double free_force = 0;
    long n_free = 0;
    double intact_force = 0;
    long n_intact = 0;
  };
  UnbalancedParts unbalanced_parts() const
  {
    return {unbalanced_sum_, n_free_, intact_force_, n_intact_};
  }

  /// What a step carries from the steps before it beside the stores: time and step, the
  /// energy accumulators, the last record's figures, the crack log. Distributed runs move it
  /// into the solver they rebuild over refilled stores when particles change ranks, and set
  /// summed figures into a solver that only reports them (rank 0's whole model).
  struct RunningState
  {
    double time = 0;
    long steps = 0;
    EnergyBalance energy;
    double damping_work = 0, max_speed = 0, unbalanced_mean = 0, unbalanced_ratio = 0;
    UnbalancedParts unbalanced;
    std::vector<CrackEvent> cracks;
    std::array<long, 2> broken_by_mode{};
    std::vector<double> applied_pressure; ///< per load (the next step's trapezoidal work)
  };
  /// Moves the state out (the crack log with it); the solver is not stepped again after.
  RunningState take_running_state();
  void set_running_state(RunningState&& s);
  /// The support reaction (force, moment) of particle i at the last step: what the work of
  /// its prescribed motion reads next step; zero for a particle without constraints.
  std::array<double, 6> support_reaction(std::size_t i) const;
  void set_support_reaction(std::size_t i, const std::array<double, 6>& reaction);

  /// Sum over the group of the particle forces of the last step: on constrained DOFs this is
  /// the support reaction, elsewhere the unbalanced force.
  Vec3 group_force(int group) const;
  /// Mean displacement of the group's particles from the reference configuration.
  Vec3 group_mean_displacement(int group) const;
  /// The pressure (Pa) load @p load applied at the last step (loads.h: p_0 factor(t) + R
  /// sigma_ref); 0 for other kinds.
  double applied_pressure(std::size_t load) const { return applied_pressure_.at(load); }
  /// sigma_ref of loads.h: the support reaction on load @p load's group along its value, over
  /// its area, at the last step.
  double reference_stress(int load) const;
  /// The part of that reaction (N) that this solver's own group members carry. A distributed
  /// run's solver holds only its rank's members, so it passes the sum over the ranks back with
  /// set_group_reaction, which reference_stress then reads instead of its own part.
  double own_group_reaction(int load) const;
  void set_group_reaction(int load, double reaction);
  /// Latest end of any load ramp: after it, loads are constant.
  double last_ramp_end() const;

  /// Continues a run on a model rebuilt at time @p time (a coupled run whose particle region
  /// grew): loads and ramps read this time, and the crack log starts with @p earlier_cracks
  /// (their bond indices in this store) and its counts by mode. Before the first step; the
  /// energy sums start anew at the next step, as at t = 0 (the caller carries the earlier ones).
  void continue_run(double time, std::vector<CrackEvent> earlier_cracks);

  /// Checkpoints (dem/core/state_archive.h, docs/checkpoint.md): saves or restores the complete
  /// state of the run between steps: the particles, the bonds (constants, state, damage), time
  /// and step, the energy accumulators, the support reactions of the last step, the crack log
  /// and each contribution's state. Restoring needs a solver built from the same case (bonds in
  /// another order, from another thread count, are matched by their pairs).
  void visit_state(StateArchive& a);
  /// Bytes the solver holds beside the particle and bond stores (dashpot resultants, supports,
  /// failure buffers).
  std::size_t memory_bytes() const;
  /// Whether every contribution can be checkpointed.
  bool checkpointable() const;

  /// Adds forces beside the bonds (contacts, walls, coupling; step_contribution.h). The
  /// contribution must outlive the solver; add before the first step.
  void add_contribution(StepContribution* contribution)
  {
    contribution->attach(p_, b_);
    contributions_.push_back(contribution);
  }

private:
  template <bool record> void dispatch_bond_forces();
  template <bool record, bool dashpots, FailureMode failure, bool smooth>
  void compute_bond_forces();
  /// On record steps a range adds its strain energy, and the sum of |F_c| and the count of its
  /// intact bonds (the unbalanced-force ratio); fracture energy on every step. `smooth`: the
  /// store has smooth joints (bonds/smooth_joint.h).
  template <bool record, bool dashpots, FailureMode failure, bool smooth>
  void bond_range(std::size_t begin, std::size_t end, double& strain, double& fracture,
                  double& intact_force, long& intact, std::vector<CrackEvent>& events);
  void drain_crack_events();
  void apply_loads();
  template <bool record> void integrate();
  /// Place of a constrained particle in constrained_.
  std::size_t slot(int particle) const;
  void partition_bonds();

  ParticleStore& p_;
  BondStore& b_;
  std::vector<Group> groups_;
  std::vector<Constraint> constraints_;
  std::vector<Load> loads_;
  SolverSettings settings_;
  std::size_t owned_ = 0; ///< particles [0, owned_) are integrated (SolverSettings)
  double time_ = 0;
  long steps_ = 0;
  EnergyBalance energy_;
  double damping_work_ = 0; ///< running damping work, half a step ahead (see integrate)
  bool dashpots_ = false;   ///< any bond with a dashpot
  /// Per particle, the sums of its bonds' records (bond_block.h: force, moment, and with
  /// dashpots their dashpot parts, whose exact work integrate books): filled by the bond loop,
  /// moved to the particles' forces after it, the dashpot parts zeroed by integrate (why one
  /// record: a bond end adds whole 256-bit vectors to one place instead of scalars to four
  /// arrays)
  std::vector<double, Eigen::aligned_allocator<double>> particle_sums_;
  bool sums_hold_evaluation_ = false; ///< evaluate_bond_forces left dashpot parts behind
  double max_speed_ = 0;
  double unbalanced_mean_ = 0; ///< mean free net force, set by integrate<true>
  double unbalanced_sum_ = 0;  ///< its sum and count
  long n_free_ = 0;
  double unbalanced_ratio_ = 0;
  double intact_force_ = 0; ///< sum of |F_c| over the intact bonds at the last record
  long n_intact_ = 0;
  std::vector<int> constrained_;    ///< particles touched by any constraint or motion load
                                    ///< (ascending; slot(i) finds particle i's place)
  std::vector<Vec3> prescribed_v_;  ///< their prescribed velocity this step (on dof_mask bits)
  std::vector<Vec3> prescribed_w_;  ///< and angular velocity
  std::vector<Vec3> constrained_v_; ///< their velocity before the step (work of supports)
  std::vector<Vec3> constrained_w_;
  using Vector6 = Eigen::Matrix<double, 6, 1>;
  std::vector<Vector6> constrained_reaction_; ///< support reactions of the previous step
  std::vector<double> applied_pressure_;      ///< per load: a pressure's value at the last step
  std::vector<double> group_reaction_;        ///< per load: the reaction over every rank, or NaN
  /// Bond ranges: phase 0 ranges run in parallel (one per chunk), then phase 1 (cut bonds
  /// between chunks s, s+1 with s even) in parallel, phase 2 (s odd), then the rest serially.
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> phases_;
  /// One failure buffer per bond range (phase_buffer_[phase] + range), reserved up front.
  std::vector<std::vector<CrackEvent>> crack_buffers_;
  std::array<std::size_t, 4> phase_buffer_{};
  std::vector<CrackEvent> cracks_;
  std::array<long, 2> broken_by_mode_{};
  std::vector<StepContribution*> contributions_;
};
} // namespace dembridge::dem
