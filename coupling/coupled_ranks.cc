// CoupledProblem's particle region on the MPI ranks (coupled_problem.h; docs/parallel.md,
// "Coupled runs on N ranks"): the blended particle model, the same on every rank after the
// set-up, is spread over the ranks by the distributed particle layer (distributed_solver.h), the
// tie is the last force of every rank's local solver. Per step each rank gives the tie's
// particle terms of the interface particles it owns (zeros for the others) to the one reduction
// the tie already makes (PointTransfer::gather_summed): every value comes from one rank, so
// every rank holds the whole right-hand side of the one-rank run bit for bit, solves the same
// factorised system and applies the tie forces to its own particles. At a record the energies
// and the band's damage are reduced over the ranks (sums in rank order, the largest index and
// the first band bond to fail by its index in the band, as one rank finds it).
#include "coupling/band_failure.h"
#include "coupling/coupled_problem.h"
#include "dem/measurements/particle_stress.h"
#include "distributed/distributed_solver.h"
#include "distributed/run_explicit.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <limits>

namespace dembridge::coupling
{
using namespace dealii;

namespace
{
std::uint64_t pair_key(std::int64_t a, std::int64_t b)
{
  return (std::uint64_t(a) << 32) | std::uint64_t(b);
}
} // namespace

const dem::ExplicitSolver* CoupledProblem::particle_solver() const
{
  return dist_ ? dist_->report() : solver_.get();
}

void CoupledProblem::gather_particles()
{
  if (dist_)
    dist_->gather(true);
}

// Rank 0 decides from the whole model; what the distributed layer cannot run keeps the
// particle region on rank 0 (named in particle_layout_reason()).
void CoupledProblem::choose_particle_layout()
{
  on_ranks_ = false;
  rank0_reason_.clear();
  if (Utilities::MPI::n_mpi_processes(comm_) < 2)
  {
    particle_layout_ = "one process";
    return;
  }
  std::string why;
  if (root_)
  {
    if (!settings_.particles_on_rank0.empty())
      why = settings_.particles_on_rank0;
    else if (adaptive_)
      why = "Coupling/Adaptive region/enabled: an adaptive region";
    else if (settings_.tying != Tying::particle)
      why = "Coupling/tying: node tying";
    else
      why = distributed::unsupported_on_ranks(model_);
  }
  why = Utilities::MPI::broadcast(comm_, why, 0);
  on_ranks_ = why.empty();
  rank0_reason_ = why;
  particle_layout_ = on_ranks_ ? "ranks" : "rank 0";
}

void CoupledProblem::make_distributed_solver()
{
  // the band's bonds by their ends' global ids (the model's indices), before the layer's
  // solvers order the model's bonds their way
  band_key_.clear();
  const auto& bonds = model_.bonds;
  for (std::size_t n = 0; n < blending_.band_bonds.size(); ++n)
  {
    const std::size_t k = blending_.band_bonds[n];
    band_key_.emplace_back(pair_key(bonds.a[k], bonds.b[k]), int(n));
  }
  std::sort(band_key_.begin(), band_key_.end());
  interface_of_.assign(model_.particles.size(), -1);
  for (std::size_t k = 0; k < interface_.size(); ++k)
    interface_of_[std::size_t(interface_[k])] = int(k);
  dist_ =
      std::make_unique<distributed::DistributedSolver>(model_, particle_solver_settings(), comm_);
  own_at_rebuild_ = -1;
}

void CoupledProblem::refresh_own_interface()
{
  auto& layer = dist_->particles();
  if (own_at_rebuild_ == layer.n_rebuilds())
    return;
  own_at_rebuild_ = layer.n_rebuilds();
  own_interface_.clear();
  const auto& ids = layer.global_ids();
  for (std::size_t i = 0; i < layer.n_owned(); ++i)
    if (const int k = interface_of_[std::size_t(ids[i])]; k >= 0)
      own_interface_.emplace_back(int(i), k);
  // by interface index: the works add up in one rank's order within each rank
  std::sort(own_interface_.begin(), own_interface_.end(),
            [](const auto& x, const auto& y) { return x.second < y.second; });
  // the band bonds this rank books (end a owned), in the local solver's order
  own_band_.clear();
  const dem::BondStore& b = layer.bonds();
  for (std::size_t k = 0; k < b.size() && !band_key_.empty(); ++k)
  {
    if (std::size_t(b.a[k]) >= layer.n_owned())
      continue;
    const auto key = pair_key(ids[std::size_t(b.a[k])], ids[std::size_t(b.b[k])]);
    const auto at = std::lower_bound(band_key_.begin(), band_key_.end(),
                                     std::pair<std::uint64_t, int>(key, -1));
    if (at != band_key_.end() && at->first == key)
      own_band_.emplace_back(int(k), at->second);
  }
  band_force_.assign(own_band_.size(), Vec3::Zero());
  band_moment_.assign(own_band_.size(), Vec3::Zero());
}

void CoupledProblem::band_forces_on_rank(const dem::ParticleStore& p)
{
  if (band_tensile_.empty())
    return;
  const dem::BondStore& b = dist_->particles().bonds();
  for (std::size_t j = 0; j < own_band_.size(); ++j)
  {
    const auto f = dem::bond_contact_force(p, b, std::size_t(own_band_[j].first));
    band_force_[j] = f.force, band_moment_[j] = f.moment;
  }
}

void CoupledProblem::band_kappa_on_rank(const dem::ParticleStore& p)
{
  band_found_ = {band_damage_.max_failure_index, -1, 0, 0, 0};
  if (band_tensile_.empty())
    return;
  const dem::BondStore& b = dist_->particles().bonds();
  for (std::size_t j = 0; j < own_band_.size(); ++j)
  {
    const auto k = std::size_t(own_band_[j].first);
    const auto n = std::size_t(own_band_[j].second);
    const double alpha = blending_.band_bond_alpha[n];
    if (alpha < 1e-9 || b.state[k] == dem::BondState::broken)
      continue;
    const double kappa = band_failure_index(
        b, k, p.position[b.b[k]] - p.position[b.a[k]], Vec3(band_force_[j] / alpha),
        Vec3(band_moment_[j] / alpha), band_tensile_[n], band_shear_[n]);
    band_found_[0] = std::max(band_found_[0], kappa);
    if (kappa >= 1 && !band_damage_.reached && (band_found_[1] < 0 || double(n) < band_found_[1]))
    {
      const Vec3 mid = 0.5 * (p.position[b.a[k]] + p.position[b.b[k]]);
      band_found_ = {band_found_[0], double(n), mid.x(), mid.y(), mid.z()};
    }
  }
}

void CoupledProblem::set_initial_state_on_ranks(const std::function<Vec3(const Vec3&)>& u,
                                                const std::function<Vec3(const Vec3&)>& v)
{
  auto& layer = dist_->particles();
  dem::ParticleStore& p = layer.particles();
  for (std::size_t i = 0; i < layer.n_owned(); ++i)
  {
    p.position[i] = p.reference_position[i] + u(p.reference_position[i]);
    p.velocity[i] = v(p.reference_position[i]);
  }
  layer.update_ghosts(); // collective
}

// check_band_damage's figures from each rank's (band_kappa_on_rank), one gather: the largest
// index, and of the bonds that passed their strength the first in the band's order (as one
// rank's loop meets them) with its midpoint.
std::vector<double> CoupledProblem::band_damage_on_ranks()
{
  std::vector<double> found(5, 0.0); // max kappa, reached, time, position
  if (band_tensile_.empty())
    return found;
  const double* mine = band_found_.data();
  const unsigned n_ranks = Utilities::MPI::n_mpi_processes(comm_);
  std::vector<double> all(5 * n_ranks);
  MPI_Allgather(mine, 5, MPI_DOUBLE, all.data(), 5, MPI_DOUBLE, comm_);
  long first = -1;
  for (unsigned r = 0; r < n_ranks; ++r)
  {
    const double* f = &all[5 * r];
    found[0] = std::max(found[0], f[0]);
    if (f[1] >= 0 && (first < 0 || f[1] < all[5 * first + 1]))
      first = long(r);
  }
  if (first >= 0)
  {
    const double* f = &all[5 * first];
    band_damage_.first_position = Vec3(f[2], f[3], f[4]);
    found[1] = 1.0, found[2] = time_, found[3] = f[2], found[4] = f[3];
  }
  return found;
}

// refresh_energies' particle figures: the layer's sums over the ranks, and the tie's works on
// each rank's own particles summed in rank order.
std::vector<double> CoupledProblem::dem_energies_on_ranks()
{
  const auto& e = dist_->energy();
  const unsigned n_ranks = Utilities::MPI::n_mpi_processes(comm_);
  const double mine[2] = {damping_particles_ - lead_damping_, work_q_particles_ - lead_q_};
  std::vector<double> all(2 * n_ranks);
  MPI_Allgather(mine, 2, MPI_DOUBLE, all.data(), 2, MPI_DOUBLE, comm_);
  double damping = 0, work = 0;
  for (unsigned r = 0; r < n_ranks; ++r)
    damping += all[2 * r], work += all[2 * r + 1];
  return {e.kinetic,
          e.strain,
          e.damping + damping + carried_.dem_damping,
          e.external + carried_.dem_external,
          e.contact_strain + e.friction + e.contact_damping + e.fracture + carried_.dem_other,
          e.initial,
          work,
          0.0};
}
} // namespace dembridge::coupling
