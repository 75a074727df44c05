#pragma once
// The coupled DEM-FE problem: a bonded-particle region tied through a handshake band to a
// deal.II elastic continuum (bridging domain method, Xiao & Belytschko 2004). Read it as a
// tutorial program with the usual verbs:
//   setup()                 the FE mesh with the particle-only region cut out, the continuum
//                           with (1 - alpha)-weighted stiffness and w_M-weighted density, the
//                           particle model with alpha-weighted bonds and w_p-weighted masses
//                           (handshake.h, blending.h), then
//   setup_interface()       interface particles located once in their FE cells (transfer.h),
//   assemble_constraints()  the tie's constraint matrix and its lumped diagonal
//                           (multipliers.h), and the common time step;
//   step(record)            one central-difference step of both sides;
//   output_results(dir, n)  the FE fields of the current state (the particles and bonds are
//                           written by the caller beside them).
//
// One step at t_n (both sides: positions u^n / x^n, velocities v^{n-1/2}), run inside the DEM
// solver's step through its StepContribution hooks (dem/solvers/step_contribution.h):
//   1. DEM bond forces (alpha-weighted) and loads at t_n                    [DEM solver]
//   2. FE forces f^n = f_ext - K_(1-alpha) u^n - c M v^{n-1/2} and the
//      trial velocities v^_I = v^{n-1/2}_I + dt M^-1 f^n                   [predict]
//   3. optional mass damping on the particles, -c m_p v_p^{n-1/2} (applied and booked by the
//      DEM solver's update, included in the tied particles' trial velocities); fine-scale
//      damping of band particles, -c_fs (1 - alpha) m_p (v_p - sum_I N_I v_I)^{n-1/2} (node
//      tying only: the part of the particle motion the FE field cannot carry)
//   4. trial velocities of the interface particles v^_p = v_p^{n-1/2} + dt F_p / m_p,
//      the tie residual rho = G v^_I - v^_p + g^n / dt and the tie forces q (multipliers.h)
//   5. the particles receive q (their update is the DEM solver's), the FE nodes -G^T q; the FE
//      side advances: v^{n+1/2}_I, u^{n+1}_I                                  [update]
//   6. DEM velocity and position update                                     [DEM solver]
// Both sides use the same step dt = safety * min(dt_DEM, dt_FE): dt_DEM the particle region's
// own critical step (dem/solvers/time_step.h, unweighted: a tied particle moves with the FE
// nodes' mass as well, so the pair is never lighter than the particle alone), dt_FE the
// bound of the continuum (Gershgorin or the element eigenvalue inequality, the smaller) with each
// node's share of the tied particles' mass added.
//
// Energy (J). Each side's energy is its weighted share: DEM kinetic 1/2 w_p m v^{n-1/2}.v^{n+1/2}
// and alpha-weighted bond strain energy; FE 1/2 v^{n-1/2}.M_w v^{n+1/2} and 1/2 u.K_(1-alpha) u.
// The tie does work q.(v^{n-1/2} + v^{n+1/2})/2 dt on the particles and the opposite on the FE
// nodes: its total, the multiplier work, vanishes when the tie holds exactly. The balance
//   E_DEM + E_FE + W_damping = E_0 + W_loads(DEM) + W_boundary(FE)
// is checked with the tie counted as internal (its work not credited).
//
// MPI: the continuum is distributed (p4est + PETSc). The particle region steps on the ranks
// too, on the distributed particle layer (distributed/distributed_solver.h: each rank its own
// particles and their ghosts, over the layer's own background mesh), with the tie as the last
// force of every rank's local solver (coupled_ranks.cc). Every rank holds the whole interface
// (transfer.h) and solves for the tie forces redundantly: a step adds one MPI_Allreduce (the FE
// velocities at the interface nodes, each from the DoF's owner, with the tie's particle terms,
// each from the particle's owner: sums of one value and zeros, so every rank has the one-rank
// numbers bit for bit) to the continuum's and the particles' own exchanges; each rank applies
// the tie forces to its own particles and DoFs. At a record the energies and the band's damage
// are reduced over the ranks and the groups' particles gathered into rank 0's model (the whole
// model, for the outputs; every particle at a snapshot). What the layer cannot do yet
// (checkpoints, an adaptive region, the contact monitor, smooth joints) keeps the particles on
// rank 0, whose DEM solver then drives the step while the other ranks run the FE phases and
// the same collectives (particle_layout() says which).
#include "coupling/adaptive_region.h"
#include "coupling/blending.h"
#include "coupling/continuum_tensor.h"
#include "coupling/handshake.h"
#include "coupling/multipliers.h"
#include "coupling/transfer.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include "fem/explicit_dynamics.h"
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace dembridge::coupling
{
/// A boundary of the FE domain moved to u = ramp(t) g(X) in the given components (the ramp is
/// a fraction, 0 to 1).
struct DrivenBoundary
{
  std::string boundary; ///< x-min ... z-max
  fem::ComponentSet components{{true, true, true}};
  std::function<Vec3(const Vec3&)> displacement;
  std::function<double(double)> ramp;
};

struct CouplingSettings
{
  HandshakeGeometry geometry;
  Vec3 element_size = Vec3::Constant(0.01); ///< FE cell size outside the band (per axis), m
  double band_element_size = 0.01;          ///< FE cell size across the band, m
  /// Cells grow away from the band by `element_growth` per cell up to this size (per axis, m;
  /// 0: no growth): a long continuum needs fine cells only near the particles.
  Vec3 far_element_size = Vec3::Zero();
  double element_growth = 1.2;
  Voigt6x6 tensor{}; ///< the continuum's stiffness (Pa)
  Tying tying = Tying::particle;
  ConstraintSolve solve = ConstraintSolve::exact;
  double solve_tolerance = 1e-12;
  unsigned int max_iterations = 200;
  double mass_damping = 0;       ///< c (1/s), both sides: -c M v, -c m v
  double fine_scale_damping = 0; ///< c_fs (1/s), band particles (node tying)
  double time_step_safety = 0.8; ///< dt = safety * min(dt_DEM, dt_FE)
  double time_step = 0;          ///< s; 0: automatic
  bool check_time_step = true;   ///< refuse a given step above the estimate
  std::vector<DrivenBoundary> driven;
  /// Why the particle region is to step on rank 0 under mpirun (the caller's reason, e.g.
  /// checkpoints); empty: on the ranks wherever the distributed particle layer can run it.
  std::string particles_on_rank0;
  /// The particle region grows where the continuum nears the particles' strength
  /// (adaptive_region.h; one process).
  AdaptiveRegionSettings adaptive;
};

} // namespace dembridge::coupling
namespace dembridge::distributed
{
class DistributedSolver;
}
namespace dembridge::coupling
{
class CoupledProblem
{
public:
  /// @p fe_parameters: the continuum (material, density, boundary conditions, loads; its mesh
  /// section is not used); @p dem_case: the particles, bonds, groups and loads. The continuum's
  /// material is replaced by settings.tensor.
  CoupledProblem(const CouplingSettings& settings, const fem::Parameters& fe_parameters,
                 const dem::CaseConfig& dem_case, MPI_Comm comm);
  ~CoupledProblem();

  void setup();
  void setup_interface();
  void assemble_constraints();
  /// One coupled step (collective). With record = true the energies are refreshed.
  void step(bool record);
  /// Checkpoints (docs/checkpoint.md; coupled_state.cc) between steps, on any number of MPI
  /// ranks with rank 0 alone at the file: the particles' state (the DEM solver's visit; they
  /// live on rank 0), the continuum's (/fe/) and the tie's (/coupling/: gap, works and their
  /// leads, energies, band damage). Saving: gather_state() on every rank (collective), then
  /// visit_state(a) on rank 0. Restoring: visit_state(a) on rank 0, then scatter_state() on
  /// every rank (collective: the continuum's parts and rank 0's tie state to each).
  void gather_state();
  void visit_state(dem::StateArchive& a);
  void scatter_state();
  MPI_Comm communicator() const { return comm_; }
  /// FE fields of the current state; returns the .pvtu name (relative to @p dir).
  std::string output_results(const std::filesystem::path& dir, unsigned int cycle);

  /// Initial state of both sides from the same fields of the reference position:
  /// u(X) and the velocity v(X) (read as v^{-1/2}). Call after setup().
  void set_initial_state(const std::function<Vec3(const Vec3&)>& u,
                         const std::function<Vec3(const Vec3&)>& v);

  double time() const { return time_; }
  long steps() const { return steps_; }
  double time_step() const { return dt_; }
  double particle_time_step() const { return dt_particles_; } ///< the particle region's own
  double fe_time_step() const { return dt_fe_; }              ///< FE bound with tied masses

  const Handshake& handshake() const { return *handshake_; }
  /// The particle model (rank 0; empty elsewhere), blended.
  dem::Model& model() { return model_; }
  const ParticleBlending& blending() const { return blending_; }
  fem::ExplicitDynamics& continuum() { return *fe_; }
  /// The continuum's parameters as the run uses them (supports, measurements).
  const fem::Parameters& fe_parameters() const { return fe_prm_; }
  /// The particle region's solver: rank 0's (on the ranks: the report solver over rank 0's
  /// model, which holds the figures summed over the ranks and the crack log at each record);
  /// null on the other ranks.
  const dem::ExplicitSolver* particle_solver() const;
  /// Where the particle region steps: "ranks" (the distributed particle layer), "rank 0" or
  /// "one process"; why not on the ranks where it could have been (empty otherwise).
  const std::string& particle_layout() const { return particle_layout_; }
  const std::string& particle_layout_reason() const { return rank0_reason_; }
  /// Collective: rank 0's model takes every particle's state and the bonds no longer intact
  /// (the particle region on the ranks; nothing to do otherwise). The groups' particles and the
  /// figures are gathered at every record.
  void gather_particles();
  const PointTransfer& transfer() const { return transfer_; }
  std::size_t n_particles() const { return n_particles_; }
  std::size_t n_interface_particles() const { return transfer_.n_points(); }

  /// Energies at the last record step (every rank holds the same values).
  struct Energies
  {
    double dem_kinetic = 0, dem_strain = 0, dem_damping = 0, dem_external = 0,
           dem_other = 0; ///< contacts, friction, fracture
    double fe_kinetic = 0, fe_strain = 0, fe_damping = 0, fe_boundary_work = 0;
    double multiplier_work_particles = 0; ///< work of the tie forces on the particles
    double multiplier_work_fe = 0;        ///< ... on the FE nodes
    double initial = 0;                   ///< E_DEM + E_FE at t = 0
    double dem_total() const { return dem_kinetic + dem_strain + dem_other; }
    double fe_total() const { return fe_kinetic + fe_strain; }
    double multiplier_work() const { return multiplier_work_particles + multiplier_work_fe; }
    /// |E_DEM + E_FE + W_damping - E_0 - W_loads - W_boundary| / largest term.
    double balance_error() const;
  };
  const Energies& energies() const { return energy_; }
  /// Largest |g| = |sum_I N_I u_I - u_p| over the interface at the last record step (m).
  double max_tie_gap() const { return max_gap_; }
  /// Tie forces q on the interface particles of the last step (N, 3 per particle, every rank).
  const std::vector<double>& tie_forces() const { return q_; }
  /// The interface particles' indices in the particle store (rank 0).
  const std::vector<int>& interface_particles() const { return interface_; }
  /// The band stays elastic (the continuum cannot carry a crack): its bonds' strengths are
  /// lifted at setup, and at every record their failure index (bond_damage.h eq. 1, on the
  /// unweighted forces F / alpha) is checked against the strengths they had. A run whose damage
  /// reaches the band says so here (rank 0 detects, every rank holds it after a record).
  struct BandDamage
  {
    std::size_t n_band_bonds = 0;       ///< bonds held elastic
    double max_failure_index = 0;       ///< largest kappa over the band's bonds and the records
    bool reached = false;               ///< kappa >= 1 somewhere in the band
    double first_time = -1;             ///< s, when it first did
    Vec3 first_position = Vec3::Zero(); ///< that bond's midpoint, m
  };
  const BandDamage& band_damage() const { return band_damage_; }
  /// The adaptive particle region (adaptive_region.h); nullptr unless enabled.
  const AdaptiveRegion* adaptive_region() const { return adaptive_.get(); }
  /// After a record step (adaptive runs): measures the utilisation and, where it passes the
  /// threshold, grows the region (region_growth.cc): both sides are rebuilt on the new region
  /// and take over the state, and the event is returned. Throws std::runtime_error when the
  /// region would have to grow through the whole body.
  std::optional<GrowthEvent> grow_region_if_due();
  /// The growth itself: the region becomes its cells and @p cells (one char per grid cell of
  /// the adaptive region); grow_region_if_due calls it, tests call it directly.
  GrowthEvent grow_region(const std::vector<char>& cells);
  const std::vector<GrowthEvent>& growth_events() const { return growth_events_; }
  /// Growth held back by `maximum particles` (the first time it was).
  struct GrowthCap
  {
    bool reached = false;
    double time = -1;          ///< s
    std::size_t particles = 0; ///< the region the growth would have made
  };
  const GrowthCap& growth_cap() const { return growth_cap_; }
  /// The run loop's growth checks (coupled_run.cc), kept here for checkpoints.
  struct GrowthChecks
  {
    long last_step = 0;     ///< the step count at the last check
    long broken_bonds = 0;  ///< the broken bonds then
    long planned_steps = 0; ///< the run's steps as counted anew at the last growth; 0: none
  };
  GrowthChecks& growth_checks() { return growth_checks_; }
  /// Fracture energy of the whole run (the particle models before each growth included), J.
  double fracture_energy() const;

  /// CG iterations of the last multiplier solve.
  unsigned int last_solve_iterations() const { return last_iterations_; }
  /// Wall seconds spent in the coupling (FE side, transfers, multipliers) and in the particles.
  double coupling_seconds() const { return coupling_seconds_; }

private:
  class Tie;
  friend class Tie;
  /// Builds both sides on the current geometry; @p adopt runs on rank 0 right after the particle
  /// model is made (before blending): a growth hands the earlier state over there. Its steps
  /// (coupled_build.cc) follow.
  void build(const std::function<void()>& adopt);
  /// The continuum on the coupled mesh; @p removed receives the cut's mass shares at its nodes.
  void build_continuum(std::vector<RemovedShare>& removed);
  void build_particles(const std::function<void()>& adopt);
  void locate_in_packing();
  void measure_bond_families();
  void refuse_motion_on_interface() const;
  std::vector<double> band_mass_ratio(const std::vector<RemovedShare>& removed);
  void blend_band(const std::vector<double>& ratio);
  void make_particle_solver();
  // The particle region on the ranks (coupled_ranks.cc).
  /// Rank 0 decides, every rank learns: the distributed layer or rank 0.
  void choose_particle_layout();
  dem::SolverSettings particle_solver_settings() const;
  void make_distributed_solver();
  /// The owned interface particles (local index, interface index), after a rebuild anew.
  void refresh_own_interface();
  void set_initial_state_on_ranks(const std::function<Vec3(const Vec3&)>& u,
                                  const std::function<Vec3(const Vec3&)>& v);
  /// The band's damage on the ranks: each rank's band bonds' forces at t_n (a record step's
  /// tie_forces: the state the bond loop read), their failure index after the update
  /// (tie_after_update, as rank 0's path reads them after the step), and the figures over the
  /// ranks (check_band_damage's found).
  void band_forces_on_rank(const dem::ParticleStore& p);
  void band_kappa_on_rank(const dem::ParticleStore& p);
  std::vector<double> band_damage_on_ranks();
  /// The particle energies summed over the ranks (refresh_energies' dem).
  std::vector<double> dem_energies_on_ranks();
  /// g = G u_I - u_p at the interface from both sides' current displacements.
  void set_tie_gap();
  /// The adaptive region's grid, packing and first cells (adaptive_region.h).
  void prepare_adaptive_region();
  /// The current region as the handshake's volume and the packing's filter.
  void apply_region();
  /// Stored energy of both sides now, between steps (growth events): strain, load potential
  /// and kinetic energy with the half-step velocities, J; @p strain receives the strain part.
  double stored_energy_now(double* strain);
  void tie_forces(dem::ParticleStore& p, double dt, bool record);
  void tie_after_update(const dem::ParticleStore& p, double dt, bool record);
  void refresh_energies(bool record);
  void compute_time_step();
  /// The tie's state (/coupling/), the same on every rank after scatter_state().
  void visit_tie(dem::StateArchive& a);

  CouplingSettings settings_;
  fem::Parameters fe_prm_;
  dem::CaseConfig dem_case_;
  MPI_Comm comm_;
  bool root_ = true;

  std::unique_ptr<Handshake> handshake_;
  std::unique_ptr<fem::ExplicitDynamics> fe_;
  dem::Model model_;
  std::vector<int> interface_; ///< the band particles (rank 0)
  ParticleBlending blending_;
  PointTransfer transfer_;
  MultiplierSolver multipliers_;
  std::unique_ptr<Tie> tie_;
  std::unique_ptr<dem::ExplicitSolver> solver_;
  std::unique_ptr<distributed::DistributedSolver> dist_; ///< the particle region on the ranks
  bool on_ranks_ = false;
  std::string particle_layout_ = "one process", rank0_reason_;
  /// (index in the particle store, interface index) of the interface particles this rank steps,
  /// by interface index: every one on rank 0's path, the owned ones on the ranks
  std::vector<std::pair<int, int>> own_interface_;
  long own_at_rebuild_ = -1;      ///< the layer's rebuild count own_interface_ was made at
  std::vector<int> interface_of_; ///< interface index of each particle (global id), or -1
  /// (pair key of the global ids of a band bond's ends, its index in blending_.band_bonds)
  std::vector<std::pair<std::uint64_t, int>> band_key_;
  std::vector<std::pair<int, int>> own_band_;  ///< (local bond, band index) booked here
  std::vector<Vec3> band_force_, band_moment_; ///< theirs at t_n of the record step
  std::array<double, 5> band_found_{};         ///< largest kappa, first band index, midpoint
  dem::ParticleStore empty_particles_;
  std::size_t n_particles_ = 0;

  double dt_ = 0, dt_particles_ = 0, dt_fe_ = 0;
  double time_ = 0;
  long steps_ = 0;

  // Per-step work arrays (sized once in assemble_constraints()).
  std::vector<double> v_trial_p_; ///< trial velocities of the interface particles
  std::vector<double> gap_;       ///< g^n per interface particle
  std::vector<double> rho_, q_;   ///< residual and tie forces
  std::vector<double> slots_, points_, slots_force_;
  std::vector<double> v_before_p_;       ///< v^{n-1/2} of the interface particles
  std::vector<dem::Vec3> damping_force_; ///< fine-scale damping of the interface particles
  fem::LA::MPI::Vector fe_force_;
  std::vector<double> alpha_p_; ///< alpha at each interface particle

  Energies energy_;
  BandDamage band_damage_;
  std::vector<double> band_tensile_, band_shear_; ///< the band bonds' own strengths, Pa
  std::vector<double> band_kappa_; ///< their failure index at the last record (adaptive runs)
  void check_band_damage();
  double work_q_particles_ = 0, damping_particles_ = 0;
  double lead_q_ = 0, lead_damping_ = 0; ///< this step's half-step leads of the two works
  double max_gap_ = 0;
  unsigned int last_iterations_ = 0;
  double coupling_seconds_ = 0;

  // Adaptive region (region_growth.cc).
  std::unique_ptr<AdaptiveRegion> adaptive_;
  /// The FE grid's lines (AdaptiveRegion::fe_lines: fine near the region, coarser elsewhere).
  GivenGridLines fine_planes_;
  std::vector<std::int32_t> packing_of_; ///< each particle's index in the envelope's packing
  std::vector<GrowthEvent> growth_events_;
  GrowthCap growth_cap_;
  GrowthChecks growth_checks_;
  /// The steps of grow_region (region_growth.cc), the earlier models handed over through
  /// GrowthHandover.
  struct GrowthHandover;
  std::vector<char> add_region_cells(const std::vector<char>& cells);
  void sample_continuum_at_joining(GrowthHandover& h);
  void hand_over_earlier_models(GrowthHandover& h);
  void adopt_particle_state(GrowthHandover& h);
  void adopt_bond_state(GrowthHandover& h);
  void renumber_crack_log(GrowthHandover& h);
  void check_loaded_groups_kept(const dem::Model& old) const;
  void continue_continuum(GrowthHandover& h);
  /// Checkpoints of an adaptive run: the region, the events, the carried works; a region that
  /// grew since the start is rebuilt before the models' state is read (region_growth.cc).
  void visit_adaptive_state(dem::StateArchive& a);
  /// The works of the models before the last growth, summed at the growth (J): the energies
  /// reported add them to the current models' own.
  struct CarriedWork
  {
    double dem_damping = 0, dem_external = 0, dem_other = 0;
    double fe_damping = 0, fe_boundary_work = 0, multiplier_work_fe = 0;
  } carried_;
};
} // namespace dembridge::coupling
