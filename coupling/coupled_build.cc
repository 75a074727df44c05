// CoupledProblem's set-up (coupled_problem.h): the tie as a contribution to the DEM solver, both
// models built on the current geometry and blended, the interface located, the tie's constraint
// matrix and the common time step, the initial state. build() runs its steps in this order:
//   1. the continuum: the lattice's tensor with (1 - alpha)-weighted stiffness and w_M-weighted
//      density on the mesh with the particle-only region cut out, the driven boundaries;
//   2. the particles (rank 0): the model as for a DEM run, the band particles, no support or
//      prescribed motion on them;
//   3. the interface particles located in their FE cells (transfer.h);
//   4. the band blended: each band particle's mass share, its bonds' alpha, its strengths held;
//   5. the constraint matrix and the common time step;
//   6. the particle solver with the tie as its last contribution.
#include "coupling/coupled_mesh.h"
#include "coupling/coupled_problem.h"
#include "distributed/distributed_solver.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dembridge::coupling
{
using namespace dealii;

namespace
{
Vec3 to_vec(const Point<3>& x)
{
  return {x[0], x[1], x[2]};
}

/// A deal.II vector-valued function from a lambda of the position.
class FieldFunction : public Function<3>
{
public:
  explicit FieldFunction(const std::function<Vec3(const Vec3&)>& f) : Function<3>(3), f_(f) {}
  double value(const Point<3>& x, const unsigned int c) const override { return f_(to_vec(x))[c]; }

private:
  const std::function<Vec3(const Vec3&)>& f_;
};

/// Which ranks run a piece of the set-up: rank 0 alone, or (the particle region on the
/// ranks, whose model every rank holds) the others after rank 0, or all of them.
enum class Ranks
{
  root,
  others,
  all
};

/// Runs @p work on @p who; an exception there is rethrown on every rank, the first failing
/// rank's (so that no rank waits in a collective call for a rank that has given up).
void run_on(MPI_Comm comm, const Ranks who, const std::function<void()>& work)
{
  const unsigned rank = Utilities::MPI::this_mpi_process(comm);
  const unsigned n_ranks = Utilities::MPI::n_mpi_processes(comm);
  std::string message;
  if (who == Ranks::all || (who == Ranks::root) == (rank == 0))
    try
    {
      work();
    }
    catch (const std::exception& e)
    {
      message = e.what();
      if (message.empty())
        message = "unknown error";
    }
  if (who == Ranks::root)
    message = Utilities::MPI::broadcast(comm, message, 0);
  else if (const unsigned first = Utilities::MPI::min(message.empty() ? n_ranks : rank, comm);
           first < n_ranks)
    message = Utilities::MPI::broadcast(comm, message, first);
  if (!message.empty())
    throw std::runtime_error(message);
}

void on_root(MPI_Comm comm, const std::function<void()>& work)
{
  run_on(comm, Ranks::root, work);
}
} // namespace

// ------------------------------------------------------------------------------------------
// The tie as seen by the DEM solver: one virtual call per step.
class CoupledProblem::Tie : public dem::StepContribution
{
public:
  explicit Tie(CoupledProblem& problem) : problem_(problem) {}
  void add_forces(dem::ParticleStore& p, double, double dt, bool record) override
  {
    problem_.tie_forces(p, dt, record);
  }
  void after_update(const dem::ParticleStore& p, double, double dt, bool record) override
  {
    problem_.tie_after_update(p, dt, record);
  }
  /// Work of the tie forces and of the coupled run's damping on the particles: done on them
  /// from outside the particle model.
  void add_energy(dem::EnergyBalance& e) const override
  {
    e.wall_work += problem_.work_q_particles_ - problem_.damping_particles_;
  }
  /// Its state is the problem's, saved in /coupling/ (CoupledProblem::visit_state).
  bool checkpointable() const override { return true; }
  void visit_state(dem::StateArchive&) override {}

private:
  CoupledProblem& problem_;
};

CoupledProblem::CoupledProblem(const CouplingSettings& settings,
                               const fem::Parameters& fe_parameters,
                               const dem::CaseConfig& dem_case, MPI_Comm comm)
    : settings_(settings), fe_prm_(fe_parameters), dem_case_(dem_case), comm_(comm),
      root_(Utilities::MPI::this_mpi_process(comm) == 0)
{
}

CoupledProblem::~CoupledProblem() = default;

void CoupledProblem::setup()
{
  check_positive_definite(settings_.tensor, "Coupling/continuum tensor");
  if (dem_case_.run.particle_damping != 0)
    throw std::runtime_error("Damping/particle damping: not available in a coupled run (its "
                             "force law cannot be tied; use Coupling/mass damping)");
  if (dem_case_.run.mass_damping != 0)
    throw std::runtime_error("Damping/mass damping: in a coupled run give it as Coupling/mass "
                             "damping (it damps both sides alike)");
  if (dem_case_.run.static_solver)
    throw std::runtime_error("Simulation/solver: a coupled run is explicit");
  if (settings_.adaptive.enabled)
    prepare_adaptive_region();
  tie_ = std::make_unique<Tie>(*this);
  build(nullptr);
}

void CoupledProblem::build(const std::function<void()>& adopt)
{
  handshake_ = std::make_unique<Handshake>(settings_.geometry);
  std::vector<RemovedShare> removed;
  build_continuum(removed);
  build_particles(adopt);
  setup_interface();
  blend_band(band_mass_ratio(removed));
  assemble_constraints();
  compute_time_step();
  make_particle_solver();
}

// The continuum: the lattice's tensor, (1 - alpha)-weighted stiffness, w_M-weighted density.
void CoupledProblem::build_continuum(std::vector<RemovedShare>& removed)
{
  fe_prm_.material = fem::MaterialModel::anisotropic;
  fe_prm_.voigt_stiffness = settings_.tensor;
  fe_prm_.problem = fem::ProblemKind::explicit_dynamics;
  if (fe_prm_.degree != 1)
    throw std::runtime_error("FEM/degree: a coupled run uses FE_Q1 (degree 1)");
  fe_ = std::make_unique<fem::ExplicitDynamics>(fe_prm_, comm_);
  const Handshake& h = *handshake_;
  fe_->set_weights([&h](const Point<3>& x) { return h.fe_stiffness_weight(to_vec(x)); },
                   [&h](const Point<3>& x) { return h.fe_mass_weight(to_vec(x)); });
  fe_->set_grid_builder(
      [this, &removed](parallel::distributed::Triangulation<3>& tria)
      {
        return make_coupled_mesh(*handshake_, settings_.element_size, settings_.band_element_size,
                                 tria, &removed, settings_.far_element_size,
                                 settings_.element_growth, adaptive_ ? &fine_planes_ : nullptr);
      });
  fe_->set_half_step_start(false); // the initial velocity is v^{-1/2}, as for the particles
  fe_->set_mass_damping(settings_.mass_damping);
  if (adaptive_)
  {
    const AdaptiveRegion& a = *adaptive_;
    fe_->add_cell_output("particle_region", [&h](const Point<3>& x)
                         { return h.in_particle_box(to_vec(x)) ? 1.0 : 0.0; });
    fe_->add_cell_output("utilisation",
                         [&a](const Point<3>& x) { return a.averaged_utilisation(to_vec(x)); });
  }
  fe_->setup();
  for (const auto& d : settings_.driven)
  {
    const FieldFunction g(d.displacement);
    fe_->prescribe_boundary_displacement(
        fem::find_boundary(fe_->boundary_names(), d.boundary, "Coupling/driven boundaries"),
        d.components, g, d.ramp);
  }
}

// The particles (rank 0; every rank's when they step on the ranks): the model as for a DEM
// run; the band particles.
void CoupledProblem::build_particles(const std::function<void()>& adopt)
{
  const auto work = [&]
  {
    model_ = dem::build_model(dem_case_);
    dt_particles_ = model_.critical.critical(); // the particle region's own
    if (adaptive_)
      locate_in_packing();
    if (adaptive_ && !adaptive_->has_families())
      measure_bond_families();
    if (adopt)
      adopt();
    interface_ = find_interface_particles(*handshake_, model_.particles);
    refuse_motion_on_interface();
  };
  on_root(comm_, work); // a case refused is refused by rank 0, once
  choose_particle_layout();
  if (on_ranks_) // the same model on every rank (the setup is replicated, as for DEM runs)
    run_on(comm_, Ranks::others, work);
  n_particles_ = Utilities::MPI::broadcast(comm_, model_.particles.size(), 0);
  dt_particles_ = Utilities::MPI::broadcast(comm_, dt_particles_, 0);
}

// Each particle's place in the envelope's packing (adaptive runs).
void CoupledProblem::locate_in_packing()
{
  packing_of_.resize(model_.particles.size());
  for (std::size_t i = 0; i < model_.particles.size(); ++i)
  {
    packing_of_[i] = adaptive_->packing_index(model_.particles.reference_position[i]);
    if (packing_of_[i] < 0)
      throw std::logic_error("adaptive region: a particle is not the packing's");
  }
}

// The packing's bond families, from the unweighted bonds of the first model (adaptive runs).
void CoupledProblem::measure_bond_families()
{
  const auto& b = model_.bonds;
  std::vector<double> ra, rb;
  for (std::size_t k = 0; k < b.size(); ++k)
    ra.push_back(model_.particles.radius[b.a[k]]), rb.push_back(model_.particles.radius[b.b[k]]);
  adaptive_->set_families(
      bond_families(b.rest_axis, b.rest_length, ra, rb, dem_case_.bonds.material));
}

// The band moves with the continuum: a support or a prescribed motion belongs on the FE side.
void CoupledProblem::refuse_motion_on_interface() const
{
  std::vector<char> tied(model_.particles.size(), 0);
  for (const int i : interface_)
    tied[i] = 1;
  auto refuse = [&](int group, const std::string& what)
  {
    for (const int i : model_.groups[group].members)
      if (tied[i])
        throw std::runtime_error("Group " + model_.groups[group].name + ": " + what +
                                 " on an interface particle (the handshake band "
                                 "moves with the continuum; support the FE side)");
  };
  for (const auto& c : model_.constraints)
    refuse(c.group, "a support");
  for (const auto& l : model_.loads)
    if (l.prescribes_motion())
      refuse(l.group, "a prescribed motion");
}

// Blending: each band particle takes the share of its mass its FE nodes lack (blending.h):
// w_p = 1 - sum_I N_I(X_p) M_I^w / M_I, with M_I the node's mass in the whole body (the cut's
// share added back on the faces of the particle-only region). Returns sum_I N_I M_I^w / M_I,
// 3 per interface particle.
std::vector<double> CoupledProblem::band_mass_ratio(const std::vector<RemovedShare>& removed)
{
  std::vector<double> weighted, full, ratio;
  transfer_.gather(fe_->lumped_mass(), weighted);
  transfer_.gather(fe_->lumped_mass_unweighted(), full);
  const double tol = 1e-9 * (settings_.geometry.domain_hi - settings_.geometry.domain_lo).norm();
  const auto& nodes = transfer_.slot_points();
  for (std::size_t s = 0; s < nodes.size(); ++s)
    for (const auto& r : removed)
      if (r.vertex.distance(nodes[s]) < tol)
        for (int c = 0; c < 3; ++c)
          full[3 * s + c] += fe_prm_.density * r.volume;
  for (std::size_t k = 0; k < weighted.size(); ++k)
    weighted[k] /= full[k];
  transfer_.interpolate(weighted, ratio);
  return ratio;
}

// The band particles' masses and bonds weighted (rank 0); the band's bonds keep their strengths
// aside and are held elastic (coupled_problem.h, BandDamage).
void CoupledProblem::blend_band(const std::vector<double>& ratio)
{
  run_on(comm_, on_ranks_ ? Ranks::all : Ranks::root,
         [&]
         {
           std::vector<double> w(interface_.size());
           for (std::size_t k = 0; k < w.size(); ++k)
             w[k] = 1.0 - ratio[3 * k];
           blending_ = blend_particles(*handshake_, interface_, w, model_.particles, model_.bonds);
           auto& b = model_.bonds;
           band_damage_.n_band_bonds = blending_.band_bonds.size();
           band_tensile_.clear();
           band_shear_.clear();
           if (b.has_failure()) // the band stays elastic: keep its strengths, lift them
             for (const std::size_t k : blending_.band_bonds)
             {
               band_tensile_.push_back(b.tensile_strength[k]);
               band_shear_.push_back(b.shear_strength[k]);
               b.tensile_strength[k] = b.shear_strength[k] =
                   std::numeric_limits<double>::infinity();
             }
         });
}

// The particle solver (rank 0) on the blended model, the tie its last contribution.
dem::SolverSettings CoupledProblem::particle_solver_settings() const
{
  dem::SolverSettings s;
  s.time_step = dt_;
  s.particle_damping = 0;
  s.mass_damping = settings_.mass_damping; // -c m v on every particle (tie_forces)
  s.threads = dem_case_.run.threads;
  return s;
}

void CoupledProblem::make_particle_solver()
{
  if (on_ranks_)
  {
    make_distributed_solver();
    dist_->add_contribution(tie_.get()); // last: it needs every other force of the step
    return;
  }
  if (!root_)
    return;
  solver_ = std::make_unique<dem::ExplicitSolver>(model_.particles, model_.bonds, model_.groups,
                                                  model_.constraints, model_.loads,
                                                  particle_solver_settings());
  for (const auto& c : model_.contributions)
    solver_->add_contribution(c.get());
  solver_->add_contribution(tie_.get()); // last: it needs every other force of the step
}

// Interface particles: centres in the band, located once in their FE cells.
void CoupledProblem::setup_interface()
{
  std::vector<Vec3> points;
  if (root_)
    for (const int i : interface_)
      points.push_back(model_.particles.reference_position[i]);
  transfer_.reinit(*fe_, points, "Coupling/particle region");
  alpha_p_.assign(transfer_.n_points(), 0.0);
  if (root_)
    for (std::size_t k = 0; k < points.size(); ++k)
      alpha_p_[k] = handshake_->alpha(points[k]);
}

// The constraint matrix S = G M^-1 G^T + diag(1 / (w_p m_p)) and its lumped diagonal.
void CoupledProblem::assemble_constraints()
{
  const std::size_t n = transfer_.n_points();
  std::vector<double> inverse_mass(n, 0.0);
  if (root_)
    for (std::size_t k = 0; k < n; ++k)
      inverse_mass[k] = 1.0 / model_.particles.mass[interface_[k]];
  if (transfer_.parallel())
    MPI_Bcast(inverse_mass.data(), int(n), MPI_DOUBLE, 0, comm_);
  std::vector<double> slot_inverse_mass;
  transfer_.gather(fe_->inverse_lumped_mass(), slot_inverse_mass);
  multipliers_.setup(transfer_, inverse_mass, slot_inverse_mass, settings_.tying, settings_.solve,
                     settings_.solve_tolerance, settings_.max_iterations);
  for (auto* v : {&v_trial_p_, &gap_, &rho_, &q_, &points_, &v_before_p_})
    v->assign(3 * n, 0.0);
  alpha_p_ = Utilities::MPI::broadcast(comm_, alpha_p_, 0);
  fe_force_.reinit(fe_->owned_dofs(), comm_);
  if ((root_ || on_ranks_) && settings_.fine_scale_damping > 0)
    damping_force_.assign(n, Vec3::Zero());
  own_interface_.clear(); // on the ranks: each rank's own, at its first step
  own_at_rebuild_ = -1;
  if (root_ && !on_ranks_)
    for (std::size_t k = 0; k < n; ++k)
      own_interface_.emplace_back(interface_[k], int(k));
}

// dt = safety * min(particle region's own step, FE bound (Gershgorin's or the element
// eigenvalue inequality's) with the tied particles' mass added to their nodes, shared by the
// shape functions).
void CoupledProblem::compute_time_step()
{
  std::vector<double> point_mass(3 * transfer_.n_points(), 0.0);
  if (root_)
    for (std::size_t k = 0; k < transfer_.n_points(); ++k)
      for (int c = 0; c < 3; ++c)
        point_mass[3 * k + c] = model_.particles.mass[interface_[k]];
  if (transfer_.parallel())
    MPI_Bcast(point_mass.data(), int(point_mass.size()), MPI_DOUBLE, 0, comm_);
  std::vector<double> slot_mass;
  transfer_.spread(point_mass, slot_mass);
  fem::LA::MPI::Vector added(fe_->owned_dofs(), comm_);
  transfer_.scatter_add(slot_mass, added);
  const double omega2 = fe_->frequency_bound(&added);
  dt_fe_ = omega2 > 0 ? 2.0 / std::sqrt(omega2) : std::numeric_limits<double>::infinity();
  const double bound = std::min(dt_particles_, dt_fe_);
  if (settings_.time_step > 0)
  {
    if (settings_.check_time_step && settings_.time_step > bound)
    {
      std::ostringstream s;
      s << "Coupling/time step: " << settings_.time_step << " s is above the stability limit "
        << bound << " s (particles " << dt_particles_ << " s, continuum " << dt_fe_ << " s)";
      throw std::runtime_error(s.str());
    }
    dt_ = settings_.time_step;
  }
  else
    dt_ = settings_.time_step_safety * bound;
}

void CoupledProblem::set_initial_state(const std::function<Vec3(const Vec3&)>& u,
                                       const std::function<Vec3(const Vec3&)>& v)
{
  const FieldFunction U(u), V(v);
  fe_->set_initial_state(U, V);
  if (root_ || on_ranks_)
  {
    auto& p = model_.particles;
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      p.position[i] = p.reference_position[i] + u(p.reference_position[i]);
      p.velocity[i] = v(p.reference_position[i]);
    }
  }
  if (dist_)
    set_initial_state_on_ranks(u, v);
  set_tie_gap();
}

// The gap between the two sides' displacements at the interface, g = G u_I - u_p.
void CoupledProblem::set_tie_gap()
{
  transfer_.gather(fe_->displacement(), slots_);
  transfer_.interpolate(slots_, points_);
  if (root_ || on_ranks_) // (every rank's model is the whole one then)
    for (std::size_t k = 0; k < transfer_.n_points(); ++k)
    {
      const int i = interface_[k];
      const Vec3 up = model_.particles.position[i] - model_.particles.reference_position[i];
      for (int c = 0; c < 3; ++c)
        gap_[3 * k + c] = points_[3 * k + c] - up[c];
    }
  if (transfer_.parallel() && !on_ranks_)
    MPI_Bcast(gap_.data(), int(gap_.size()), MPI_DOUBLE, 0, comm_);
}
} // namespace dembridge::coupling
