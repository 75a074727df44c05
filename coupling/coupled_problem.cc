// CoupledProblem's step (coupled_problem.h): the tie forces and the FE update inside the DEM
// solver's step, the band's damage check and the energies at a record. Its set-up is in
// coupled_build.cc, its checkpoint state in coupled_state.cc, the adaptive region's growth in
// region_growth.cc.
#include "coupling/coupled_problem.h"

#include <deal.II/base/mpi.h>

#include "coupling/band_failure.h"
#include "distributed/distributed_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace dembridge::coupling
{
using namespace dealii;

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
// One step.
void CoupledProblem::step(bool record)
{
  record = record || steps_ == 0; // the first step fixes the initial energy (as the DEM solver)
  if (dist_)
    dist_->step(record); // every rank's local solver calls tie_forces and tie_after_update
  else if (root_)
    solver_->step(record); // calls tie_forces and tie_after_update
  else
  {
    tie_forces(empty_particles_, dt_, record);
    tie_after_update(empty_particles_, dt_, record);
  }
  time_ += dt_;
  ++steps_;
  if (!record)
    return;
  refresh_energies(true);
  if (dist_) // the groups' particles, the figures and the cracks into rank 0's model
    dist_->gather(false);
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
  if (dist_) // this rank's particles' terms, zeros for the others' (summed in the gather)
  {
    refresh_own_interface();
    std::fill(rho_.begin(), rho_.end(), 0.0);
    if (record)
      band_forces_on_rank(p);
  }
  // The mass damping -c m v^{n-1/2} acts on every particle in the DEM solver's update (its
  // energy booked there); the trial velocities of the tied particles include it.
  const double c = settings_.mass_damping;
  for (const auto& [i, k] : own_interface_)
  {
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
  // rho = G v^_I - v^_p + g^n / dt; the particles' part reaches every rank with the FE values
  // (the step's one reduction)
  if (dist_)
    transfer_.gather_summed(fe_->trial_velocity(), slots_, rho_);
  else
    transfer_.gather(fe_->trial_velocity(), slots_, rho_);
  transfer_.interpolate(slots_, points_);
  for (std::size_t k = 0; k < 3 * n; ++k)
    rho_[k] += points_[k];
  last_iterations_ = multipliers_.solve(rho_, dt, q_);

  // the works summed in locals: members would be stored at every term (the force array could
  // alias them for the compiler), a chain through memory
  double work_q = work_q_particles_, lead_q = 0;
  for (const auto& [i, k] : own_interface_)
  {
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
  if (!damping_force_.empty()) // dissipated: -F_d . (v^{n-1/2} + v^{n+1/2}) / 2 dt
  {
    lead_damping_ = 0;
    for (const auto& [i, k] : own_interface_)
    {
      const Vec3& v1 = p.velocity[i];
      const Vec3 v0(v_before_p_[3 * k], v_before_p_[3 * k + 1], v_before_p_[3 * k + 2]);
      damping_particles_ -= damping_force_[k].dot(v0 + v1) * 0.5 * dt;
      lead_damping_ -= damping_force_[k].dot(v1) * 0.5 * dt;
    }
  }
  if (record && dist_)
    band_kappa_on_rank(p);
  if (record) // the tie's actual displacement gap, for the record
  {
    transfer_.gather(fe_->displacement(), slots_);
    transfer_.interpolate(slots_, points_);
    double gap = 0;
    for (const auto& [i, k] : own_interface_)
    {
      const Vec3 up = p.position[i] - p.reference_position[i];
      gap =
          std::max(gap, (Vec3(points_[3 * k], points_[3 * k + 1], points_[3 * k + 2]) - up).norm());
    }
    max_gap_ = dist_ ? Utilities::MPI::max(gap, comm_) : Utilities::MPI::broadcast(comm_, gap, 0);
  }
  coupling_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The band's bonds against the strengths they had (coupled_problem.h, BandDamage): their forces
// are alpha times a whole bond's, so the stress of the bond they stand for is that of F / alpha.
void CoupledProblem::check_band_damage()
{
  std::vector<double> found(5, 0.0); // max kappa, reached, time, position
  if (dist_)
    found = band_damage_on_ranks(); // the same on every rank
  else if (root_ && !band_tensile_.empty())
  {
    if (adaptive_)
      band_kappa_.assign(blending_.band_bonds.size(), 0.0);
    const auto& b = model_.bonds;
    const auto& p = model_.particles;
    double largest = band_damage_.max_failure_index;
    for (std::size_t n = 0; n < blending_.band_bonds.size(); ++n)
    {
      const std::size_t k = blending_.band_bonds[n];
      const double alpha = blending_.band_bond_alpha[n];
      if (alpha < 1e-9 || b.state[k] == dem::BondState::broken)
        continue;
      const double kappa = band_failure_index(b, k, p.position[b.b[k]] - p.position[b.a[k]],
                                              Vec3(b.force[k] / alpha), Vec3(b.moment[k] / alpha),
                                              band_tensile_[n], band_shear_[n]);
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
  if (transfer_.parallel() && !dist_)
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
  if (dist_)
    dem = dem_energies_on_ranks(); // the same on every rank
  else if (root_)
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
  if (transfer_.parallel() && !dist_)
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
