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
#include <stdexcept>

namespace dembridge::coupling
{
void CoupledProblem::gather_state()
{
  if (on_ranks_) // (the caller keeps such runs' particles on rank 0)
    throw std::logic_error("checkpoints of a coupled run with its particles on the ranks");
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

// The adaptive region's part: its cells and fine zone, the growth checks, the cap, the works
// carried over earlier growths and the events; a region that grew before the checkpoint
// rebuilds both models on it before their state is read.
void CoupledProblem::visit_adaptive_state(dem::StateArchive& a)
{
  dem::StateGroup group(a, "adaptive");
  const std::vector<char> cells_now = adaptive_->cells();
  const auto zone_now = adaptive_->fine_zone();
  adaptive_->visit_state(a);
  a.io("last_check_step", growth_checks_.last_step);
  a.io("broken_bonds_at_check", growth_checks_.broken_bonds);
  a.io("planned_steps", growth_checks_.planned_steps);
  a.io("cap_reached", growth_cap_.reached);
  a.io("cap_time", growth_cap_.time);
  a.io("cap_particles", growth_cap_.particles);
  {
    dem::StateGroup works(a, "carried_work");
    a.io("dem_damping", carried_.dem_damping);
    a.io("dem_external", carried_.dem_external);
    a.io("dem_other", carried_.dem_other);
    a.io("fe_damping", carried_.fe_damping);
    a.io("fe_boundary_work", carried_.fe_boundary_work);
    a.io("multiplier_work_fe", carried_.multiplier_work_fe);
  }
  // the events, 16 numbers each
  constexpr std::size_t fields = 16;
  std::vector<double> events;
  for (const auto& e : growth_events_)
    events.insert(events.end(),
                  {e.time, double(e.step), double(e.cells_added), double(e.region_cells),
                   double(e.particles_added), double(e.n_particles), double(e.bonds_added),
                   double(e.n_bonds), double(e.marked_cells), double(e.marked_by_bonds),
                   e.max_utilisation, e.energy_before, e.energy_after, e.strain_energy, e.time_step,
                   e.wall_seconds});
  a.io("events", events);
  if (!a.loading())
    return;
  if (events.size() % fields != 0)
    throw dem::InputError(a.where() + "events: " + std::to_string(events.size()) +
                          " numbers, not a whole number of events");
  growth_events_.clear();
  for (std::size_t k = 0; k < events.size(); k += fields)
  {
    const double* v = events.data() + k;
    GrowthEvent e;
    e.time = v[0];
    e.step = long(v[1]);
    e.cells_added = std::size_t(v[2]), e.region_cells = std::size_t(v[3]);
    e.particles_added = std::size_t(v[4]), e.n_particles = std::size_t(v[5]);
    e.bonds_added = std::size_t(v[6]), e.n_bonds = std::size_t(v[7]);
    e.marked_cells = std::size_t(v[8]), e.marked_by_bonds = std::size_t(v[9]);
    e.max_utilisation = v[10];
    e.energy_before = v[11], e.energy_after = v[12], e.strain_energy = v[13];
    e.time_step = v[14], e.wall_seconds = v[15];
    growth_events_.push_back(e);
  }
  if (adaptive_->cells() == cells_now && adaptive_->fine_zone() == zone_now)
    return;
  // the region grew before the checkpoint: both models anew on it (their state is read next)
  solver_.reset();
  auto old_fe = std::move(fe_);
  auto old_handshake = std::move(handshake_);
  apply_region();
  build(nullptr);
}
} // namespace dembridge::coupling
