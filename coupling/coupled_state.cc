// CoupledProblem's checkpoint state (coupled_problem.h: visit_state; docs/checkpoint.md).
// Between steps the tie carries the gap g^n (the next residual reads it), the works of the tie
// forces and of the fine-scale damping on the particles with their half-step leads, the last
// record's energies (E_0 among them), the largest gap of the last record and the band damage so
// far; the particles and the continuum carry their own (the DEM solver's visit, /fe/). The
// trial and earlier velocities, the residual, the slot buffers, the FE force vector and the
// damping forces are overwritten in each step before they are read; the multipliers' solver
// keeps no state between steps (CG starts from the lumped solution), the transfer and the
// factorisation are rebuilt from the case. On several MPI ranks rank 0 reads and writes the
// file; the other ranks take its tie state by broadcast (every rank holds the same tie state).
#include "coupling/coupled_problem.h"

namespace dembridge::coupling
{
void CoupledProblem::gather_state()
{
  fe_->gather_state();
}

void CoupledProblem::visit_state(dem::StateArchive& a)
{
  if (adaptive_)
    visit_adaptive_state(a); // first: the models below are the region's
  solver_->visit_state(a);   // /particles/, /bonds/, /solver/ (rank 0's)
  fe_->visit_state(a);       // /fe/
  visit_tie(a);              // /coupling/
}

void CoupledProblem::scatter_state()
{
  fe_->scatter_state();
  fem::broadcast_state(comm_, [this](dem::StateArchive& a) { visit_tie(a); });
}

void CoupledProblem::visit_tie(dem::StateArchive& a)
{
  dem::StateGroup group(a, "coupling");
  double dt = dt_;
  a.io("time_step", dt);
  // why: the same case gives the same step to the last bit; another step is another run
  if (a.loading() && dt != dt_)
    throw dem::InputError(a.where() + "time_step: " + std::to_string(dt) +
                          " s in the checkpoint, " + std::to_string(dt_) + " s in this run");
  a.io("time", time_);
  a.io("steps", steps_);
  a.io_sized("gap", gap_);
  a.io_sized("tie_forces", q_);
  a.io("work_q_particles", work_q_particles_);
  a.io("damping_particles", damping_particles_);
  a.io("lead_q", lead_q_);
  a.io("lead_damping", lead_damping_);
  a.io("max_gap", max_gap_);
  int iterations = int(last_iterations_);
  a.io("last_solve_iterations", iterations);
  last_iterations_ = unsigned(iterations);
  {
    dem::StateGroup energies(a, "energy");
    Energies& e = energy_;
    a.io("dem_kinetic", e.dem_kinetic);
    a.io("dem_strain", e.dem_strain);
    a.io("dem_damping", e.dem_damping);
    a.io("dem_external", e.dem_external);
    a.io("dem_other", e.dem_other);
    a.io("fe_kinetic", e.fe_kinetic);
    a.io("fe_strain", e.fe_strain);
    a.io("fe_damping", e.fe_damping);
    a.io("fe_boundary_work", e.fe_boundary_work);
    a.io("multiplier_work_particles", e.multiplier_work_particles);
    a.io("multiplier_work_fe", e.multiplier_work_fe);
    a.io("initial", e.initial);
  }
  {
    dem::StateGroup band(a, "band_damage");
    BandDamage& b = band_damage_;
    std::size_t n_band = b.n_band_bonds;
    a.io("n_band_bonds", n_band);
    if (a.loading() && root_ && n_band != b.n_band_bonds) // rank 0 built the band
      throw dem::InputError(a.where() + "n_band_bonds: " + std::to_string(n_band) +
                            " in the checkpoint, " + std::to_string(b.n_band_bonds) +
                            " in this model");
    a.io("max_failure_index", b.max_failure_index);
    a.io("reached", b.reached);
    a.io("first_time", b.first_time);
    a.io("first_position", b.first_position);
  }
}
} // namespace dembridge::coupling
