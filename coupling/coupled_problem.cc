#include "coupling/coupled_problem.h"
#include "coupling/coupled_mesh.h"

#include <deal.II/base/mpi.h>

#include "dem/bonds/bond_stress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
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

/// Runs @p work on rank 0 only; an exception there is rethrown on every rank (so that no rank
/// waits in a collective call for a rank that has given up).
void on_root(MPI_Comm comm, const std::function<void()>& work)
{
  std::string message;
  if (Utilities::MPI::this_mpi_process(comm) == 0)
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
  message = Utilities::MPI::broadcast(comm, message, 0);
  if (!message.empty())
    throw std::runtime_error(message);
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

double CoupledProblem::Energies::balance_error() const
{
  const double in = initial + dem_external + fe_boundary_work;
  const double stored =
      dem_kinetic + dem_strain + dem_other + dem_damping + fe_kinetic + fe_strain + fe_damping;
  const double largest = std::max({std::abs(dem_kinetic), std::abs(dem_strain), std::abs(dem_other),
                                   std::abs(dem_damping), std::abs(fe_kinetic), std::abs(fe_strain),
                                   std::abs(fe_damping), std::abs(initial), std::abs(dem_external),
                                   std::abs(fe_boundary_work)});
  return largest > 0 ? std::abs(stored - in) / largest : 0.0;
}

// ------------------------------------------------------------------------------------------
// Setup: both models, blended.
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
  // The continuum: the lattice's tensor, (1 - alpha)-weighted stiffness, w_M-weighted density.
  fe_prm_.material = fem::MaterialModel::anisotropic;
  fe_prm_.voigt_stiffness = settings_.tensor;
  fe_prm_.problem = fem::ProblemKind::explicit_dynamics;
  if (fe_prm_.degree != 1)
    throw std::runtime_error("FEM/degree: a coupled run uses FE_Q1 (degree 1)");
  fe_ = std::make_unique<fem::ExplicitDynamics>(fe_prm_, comm_);
  const Handshake& h = *handshake_;
  fe_->set_weights([&h](const Point<3>& x) { return h.fe_stiffness_weight(to_vec(x)); },
                   [&h](const Point<3>& x) { return h.fe_mass_weight(to_vec(x)); });
  std::vector<RemovedShare> removed;
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

  // The particles (rank 0): the model as for a DEM run; the band particles.
  on_root(comm_,
          [&]
          {
            model_ = dem::build_model(dem_case_);
            dt_particles_ = model_.critical.critical(); // the particle region's own
            if (adaptive_) // each particle's place in the envelope's packing
            {
              packing_of_.resize(model_.particles.size());
              for (std::size_t i = 0; i < model_.particles.size(); ++i)
              {
                packing_of_[i] = adaptive_->packing_index(model_.particles.reference_position[i]);
                if (packing_of_[i] < 0)
                  throw std::logic_error("adaptive region: a particle is not the packing's");
              }
            }
            if (adaptive_ && !adaptive_->has_families()) // the packing's bonds, unweighted
            {
              const auto& b = model_.bonds;
              std::vector<double> ra, rb;
              for (std::size_t k = 0; k < b.size(); ++k)
                ra.push_back(model_.particles.radius[b.a[k]]),
                    rb.push_back(model_.particles.radius[b.b[k]]);
              adaptive_->set_families(
                  bond_families(b.rest_axis, b.rest_length, ra, rb, dem_case_.bonds.material));
            }
            if (adopt)
              adopt();
            interface_ = find_interface_particles(h, model_.particles);
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
          });
  n_particles_ = Utilities::MPI::broadcast(comm_, model_.particles.size(), 0);
  dt_particles_ = Utilities::MPI::broadcast(comm_, dt_particles_, 0);

  setup_interface();
  // Blending: each band particle takes the share of its mass its FE nodes lack (blending.h):
  // w_p = 1 - sum_I N_I(X_p) M_I^w / M_I, with M_I the node's mass in the whole body (the cut's
  // share added back on the faces of the particle-only region).
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
    on_root(comm_,
            [&]
            {
              std::vector<double> w(interface_.size());
              for (std::size_t k = 0; k < w.size(); ++k)
                w[k] = 1.0 - ratio[3 * k];
              blending_ = blend_particles(h, interface_, w, model_.particles, model_.bonds);
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
  assemble_constraints();
  compute_time_step();

  if (root_)
  {
    dem::SolverSettings s;
    s.time_step = dt_;
    s.particle_damping = 0;
    s.mass_damping = settings_.mass_damping; // -c m v on every particle (tie_forces)
    s.threads = dem_case_.run.threads;
    solver_ = std::make_unique<dem::ExplicitSolver>(model_.particles, model_.bonds, model_.groups,
                                                    model_.constraints, model_.loads, s);
    for (const auto& c : model_.contributions)
      solver_->add_contribution(c.get());
    solver_->add_contribution(tie_.get()); // last: it needs every other force of the step
  }
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
  if (root_ && settings_.fine_scale_damping > 0)
    damping_force_.assign(n, Vec3::Zero());
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
  if (root_)
  {
    auto& p = model_.particles;
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      p.position[i] = p.reference_position[i] + u(p.reference_position[i]);
      p.velocity[i] = v(p.reference_position[i]);
    }
  }
  // the gap between the two sides' initial displacements at the interface
  transfer_.gather(fe_->displacement(), slots_);
  transfer_.interpolate(slots_, points_);
  if (root_)
    for (std::size_t k = 0; k < transfer_.n_points(); ++k)
    {
      const int i = interface_[k];
      const Vec3 up = model_.particles.position[i] - model_.particles.reference_position[i];
      for (int c = 0; c < 3; ++c)
        gap_[3 * k + c] = points_[3 * k + c] - up[c];
    }
  if (transfer_.parallel())
    MPI_Bcast(gap_.data(), int(gap_.size()), MPI_DOUBLE, 0, comm_);
}

// ------------------------------------------------------------------------------------------
// One step.
void CoupledProblem::step(bool record)
{
  record = record || steps_ == 0; // the first step fixes the initial energy (as the DEM solver)
  if (root_)
    solver_->step(record); // calls tie_forces and tie_after_update
  else
  {
    tie_forces(empty_particles_, dt_, record);
    tie_after_update(empty_particles_, dt_, record);
  }
  time_ += dt_;
  ++steps_;
  if (record)
    refresh_energies(true);
}

// Steps 2-5 of the file comment: FE forces and trial velocities, damping, the tie forces, the
// FE update.
void CoupledProblem::tie_forces(dem::ParticleStore& p, const double dt, const bool record)
{
  const auto start = std::chrono::steady_clock::now();
  fe_->predict(dt);
  const std::size_t n = transfer_.n_points();
  const bool fine_scale = settings_.fine_scale_damping > 0;
  if (fine_scale) // G v^{n-1/2}: the FE velocity at the interface particles
  {
    transfer_.gather(fe_->velocity(), slots_);
    transfer_.interpolate(slots_, points_);
  }
  if (root_)
  {
    // The mass damping -c m v^{n-1/2} acts on every particle in the DEM solver's update (its
    // energy booked there); the trial velocities of the tied particles include it.
    const double c = settings_.mass_damping;
    for (std::size_t k = 0; k < n; ++k)
    {
      const int i = interface_[k];
      if (fine_scale) // the part of the particle velocity the FE field does not carry
      {
        const Vec3 fine =
            p.velocity[i] - Vec3(points_[3 * k], points_[3 * k + 1], points_[3 * k + 2]);
        damping_force_[k] = -settings_.fine_scale_damping * (1 - alpha_p_[k]) * p.mass[i] * fine;
        p.force[i] += damping_force_[k];
      }
      const Vec3 v_hat = (1 - c * dt) * p.velocity[i] + (dt / p.mass[i]) * p.force[i];
      for (int d = 0; d < 3; ++d)
      {
        v_before_p_[3 * k + d] = p.velocity[i][d];
        v_trial_p_[3 * k + d] = v_hat[d];
        rho_[3 * k + d] = gap_[3 * k + d] / dt - v_hat[d];
      }
    }
  }
  if (transfer_.parallel())
    MPI_Bcast(rho_.data(), int(rho_.size()), MPI_DOUBLE, 0, comm_);
  // rho = G v^_I - v^_p + g^n / dt
  transfer_.gather(fe_->trial_velocity(), slots_);
  transfer_.interpolate(slots_, points_);
  for (std::size_t k = 0; k < 3 * n; ++k)
    rho_[k] += points_[k];
  last_iterations_ = multipliers_.solve(rho_, dt, q_);

  // the works summed in locals: members would be stored at every term (the force array could
  // alias them for the compiler), a chain through memory
  double work_q = work_q_particles_, lead_q = 0;
  if (root_)
    for (std::size_t k = 0; k < n; ++k)
    {
      const int i = interface_[k];
      const Vec3 q(q_[3 * k], q_[3 * k + 1], q_[3 * k + 2]);
      p.force[i] += q; // the solver's update gives v^_p + dt q / m_p
      for (int d = 0; d < 3; ++d)
      {
        const double v1 = v_trial_p_[3 * k + d] + dt * q[d] / p.mass[i];
        work_q += q[d] * 0.5 * (v_before_p_[3 * k + d] + v1) * dt;
        lead_q += q[d] * 0.5 * v1 * dt; // the half-step lead (fem/explicit_dynamics.cc)
      }
    }
  work_q_particles_ = work_q;
  lead_q_ = lead_q;
  // the FE nodes take -G^T q (= -M y after a factorised solve: no spread)
  if (!multipliers_.slot_reaction(slots_force_))
  {
    transfer_.spread(q_, slots_force_);
    for (auto& f : slots_force_)
      f = -f;
  }
  fe_force_ = 0;
  transfer_.scatter_add(slots_force_, fe_force_);
  fe_->apply_force(fe_force_, dt);
  fe_->update(dt, record);
  // the gap after the step: g^{n+1} = dt (rho - dt S q)
  const auto& Sq = multipliers_.schur_q();
  for (std::size_t k = 0; k < 3 * n; ++k)
    gap_[k] = dt * (rho_[k] - dt * Sq[k]);
  coupling_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void CoupledProblem::tie_after_update(const dem::ParticleStore& p, const double dt,
                                      const bool record)
{
  const auto start = std::chrono::steady_clock::now();
  if (root_ && !damping_force_.empty()) // dissipated: -F_d . (v^{n-1/2} + v^{n+1/2}) / 2 dt
  {
    lead_damping_ = 0;
    for (std::size_t k = 0; k < interface_.size(); ++k)
    {
      const Vec3& v1 = p.velocity[interface_[k]];
      const Vec3 v0(v_before_p_[3 * k], v_before_p_[3 * k + 1], v_before_p_[3 * k + 2]);
      damping_particles_ -= damping_force_[k].dot(v0 + v1) * 0.5 * dt;
      lead_damping_ -= damping_force_[k].dot(v1) * 0.5 * dt;
    }
  }
  if (record) // the tie's actual displacement gap, for the record
  {
    transfer_.gather(fe_->displacement(), slots_);
    transfer_.interpolate(slots_, points_);
    double gap = 0;
    if (root_)
      for (std::size_t k = 0; k < transfer_.n_points(); ++k)
      {
        const int i = interface_[k];
        const Vec3 up = p.position[i] - p.reference_position[i];
        gap = std::max(gap,
                       (Vec3(points_[3 * k], points_[3 * k + 1], points_[3 * k + 2]) - up).norm());
      }
    max_gap_ = Utilities::MPI::broadcast(comm_, gap, 0);
  }
  coupling_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The band's bonds against the strengths they had (coupled_problem.h, BandDamage): their forces
// are alpha times a whole bond's, so the stress of the bond they stand for is that of F / alpha.
void CoupledProblem::check_band_damage()
{
  std::vector<double> found(5, 0.0); // max kappa, reached, time, position
  if (root_ && !band_tensile_.empty())
  {
    if (adaptive_)
      band_kappa_.assign(blending_.band_bonds.size(), 0.0);
    const auto& b = model_.bonds;
    const auto& p = model_.particles;
    const auto& law = b.failure;
    double largest = band_damage_.max_failure_index;
    for (std::size_t n = 0; n < blending_.band_bonds.size(); ++n)
    {
      const std::size_t k = blending_.band_bonds[n];
      const double alpha = blending_.band_bond_alpha[n];
      if (alpha < 1e-9 || b.state[k] == dem::BondState::broken)
        continue;
      const Vec3 chord = p.position[b.b[k]] - p.position[b.a[k]];
      const Vec3 e = chord.normalized(), F = b.force[k] / alpha, M = b.moment[k] / alpha;
      const auto s = dem::bond_stress(F.data(), M.data(), e.data(), b.radius[k], law.moment_factor);
      const double tau_max = dem::shear_strength(law, band_shear_[n], s.normal_force, s.area);
      const double kappa = std::max(s.tensile / band_tensile_[n], s.shear / tau_max);
      if (adaptive_)
        band_kappa_[n] = kappa;
      largest = std::max(largest, kappa);
      if (kappa >= 1 && !band_damage_.reached && found[1] == 0)
      {
        const Vec3 mid = 0.5 * (p.position[b.a[k]] + p.position[b.b[k]]);
        found = {kappa, 1.0, time_, mid.x(), mid.y()};
        band_damage_.first_position = mid;
      }
    }
    found[0] = largest;
  }
  if (transfer_.parallel())
    MPI_Bcast(found.data(), int(found.size()), MPI_DOUBLE, 0, comm_);
  band_damage_.max_failure_index = std::max(band_damage_.max_failure_index, found[0]);
  if (found[1] != 0 && !band_damage_.reached)
  {
    band_damage_.reached = true;
    band_damage_.first_time = found[2];
    if (root_)
    {
      const Vec3& x = band_damage_.first_position;
      std::printf("coupling: WARNING: damage reached the handshake band at t = %.4g s (a band "
                  "bond at %.4g, %.4g, %.4g m passed its strength; the band is held elastic, "
                  "so the crack cannot go on into the continuum: enlarge the particle region)\n",
                  found[2], x.x(), x.y(), x.z());
      std::fflush(stdout);
    }
  }
}

void CoupledProblem::refresh_energies(const bool)
{
  check_band_damage();
  std::vector<double> dem(8, 0.0);
  if (root_)
  {
    const auto& e = solver_->energy();
    dem = {e.kinetic,
           e.strain,
           e.damping + damping_particles_ - lead_damping_ + carried_.dem_damping,
           e.external + carried_.dem_external,
           e.contact_strain + e.friction + e.contact_damping + e.fracture + carried_.dem_other,
           e.initial,
           work_q_particles_ - lead_q_,
           0.0};
  }
  if (transfer_.parallel())
    MPI_Bcast(dem.data(), int(dem.size()), MPI_DOUBLE, 0, comm_);
  const auto& f = fe_->energies();
  energy_.dem_kinetic = dem[0];
  energy_.dem_strain = dem[1];
  energy_.dem_damping = dem[2];
  energy_.dem_external = dem[3];
  energy_.dem_other = dem[4];
  energy_.multiplier_work_particles = dem[6];
  energy_.fe_kinetic = f.kinetic_shadow;
  energy_.fe_strain = f.strain + f.load_potential;
  energy_.fe_damping = f.damping + carried_.fe_damping;
  energy_.fe_boundary_work = f.boundary_work + carried_.fe_boundary_work;
  energy_.multiplier_work_fe = f.outside_work + carried_.multiplier_work_fe;
  if (steps_ == 1) // step 0 just completed: the state at t_0
    energy_.initial = dem[5] + f.shadow_total();
}

std::string CoupledProblem::output_results(const std::filesystem::path& dir,
                                           const unsigned int cycle)
{
  return fe_->output(dir, cycle, time_);
}
} // namespace dembridge::coupling
