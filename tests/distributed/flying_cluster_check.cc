// distributed_check (distributed_check.cc, under mpirun on 1, 2 and 3 ranks):
//   distributed_check flying_cluster
// A bonded HCP cluster, spinning and vibrating, flies along x across the background mesh: its
// particles change cells and ranks many times (the check asserts migrations, particles changing
// ranks and bonds across ranks at several records). Against the same model stepped on one rank by
// dem/'s ExplicitSolver:
//  - every bond survives with its state: the bonds booked over the ranks are the model's, all
//    intact, and their constants as formed;
//  - at every record (each 200 steps) every energy term (kinetic, strain, bond dashpots' damping,
//    initial and the others, zero here) agree to 1e-10 of the largest term, and the energy balance
//    error to 1e-12 (absolute, of a relative error);
//  - every particle's final position agrees to 1e-10 of the distance flown;
//  - on several ranks the mesh is repartitioned (the cluster flies into a rank's cells).
//   distributed_check repartitioned_cluster
// The same with r = 2.5 mm (718 particles, 2000 steps): besides, the repartitions start from an
// imbalance (most owned particles over their mean) above DistributedParticles::max_imbalance and
// each leaves it at most that (with 68 particles p4est's cell families are too coarse for it).
#include "dem/bonds/bonding.h"
#include "dem/contacts/contact_forces.h"
#include "dem/model/model.h"
#include "dem/packing/packings.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/time_step.h"
#include "distributed/bond_piece.h"
#include "distributed/bond_records.h"
#include "distributed/distributed_solver.h"
#include "distributed_check.h"
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deal.II/base/mpi.h>
#include <iostream>
#include <map>
#include <random>
#include <string>

namespace dembridge::distributed_check
{
using dem::Vec3;

/// A bonded HCP cluster (r = 5 mm, or @p radius) with bond dashpots, flying at 20 m/s along x
/// while it spins and vibrates (seeded random velocities and angular velocities on top).
dem::Model flying_cluster(double radius = 5e-3)
{
  dem::Model m;
  dem::ParticleSource src;
  src.kind = dem::ParticleSource::Kind::hcp;
  src.radius = radius;
  src.box_size = Vec3(0.05, 0.04, 0.04);
  dem::generate_particles(src, m.particles);
  dem::BondMaterial mat;
  mat.youngs_modulus = 4e9;
  dem::form_bonds(m.particles, m.bonds, mat, 1.0);
  dem::assign_bond_damping(m.particles, m.bonds, 0.001);
  std::mt19937 rng(7);
  std::normal_distribution<double> n01(0, 1);
  for (std::size_t i = 0; i < m.particles.size(); ++i)
  {
    m.particles.velocity[i] = Vec3(20, 0, 0) + 3 * Vec3(n01(rng), n01(rng), n01(rng));
    m.particles.angular_velocity[i] = Vec3(30, 0, 0) + 300 * Vec3(n01(rng), n01(rng), n01(rng));
  }
  m.critical = dem::estimate_critical_time_step(m.particles, m.bonds);
  m.time_step = 0.5 * m.critical.critical();
  return m;
}

/// @p balanced: the check also asserts that a repartition leaves the owned particles balanced
/// within DistributedParticles::max_imbalance (a cluster of many particles a rank: p4est keeps
/// the 8 children of a cell on one rank, some 16 particles here).
int flying_cluster_check(MPI_Comm comm, double radius, long steps, bool balanced)
{
  const unsigned n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const long record_every = steps / 20;
  dem::Model serial = flying_cluster(radius), model = flying_cluster(radius);
  // the mesh over the whole flight (20 m/s, some 0.1 m for r = 5 mm): cells the cut-off
  // wide, the cluster crossing a dozen of them
  const double width = 1.25 * 2 * radius;
  const distributed::BackgroundGrid grid =
      distributed::make_background_grid(Vec3(-0.03, -0.03, -0.03), Vec3(0.2, 0.07, 0.07), width);
  dem::ExplicitSolver one(serial.particles, serial.bonds, {}, {}, {}, {serial.time_step});
  distributed::DistributedSolver ranks(model, {model.time_step}, comm, &grid);
  // bonds with a ghost end on this rank
  auto bonds_across = [&]
  {
    const auto& b = ranks.particles().bonds();
    const std::size_t owned = ranks.particles().n_owned();
    long n = 0;
    for (std::size_t k = 0; k < b.size(); ++k)
      n += std::size_t(b.a[k]) >= owned || std::size_t(b.b[k]) >= owned;
    return dealii::Utilities::MPI::sum(n, comm) / 2;
  };
  long booked_at_start = 0;
  for (std::size_t k = 0; k < ranks.particles().bonds().size(); ++k)
    booked_at_start += std::size_t(ranks.particles().bonds().a[k]) < ranks.particles().n_owned();
  booked_at_start = dealii::Utilities::MPI::sum(booked_at_start, comm);
  const long across = bonds_across();
  // in step, recording every 200 steps: the energy terms against one rank's at each record
  double worst_energy = 0, worst_balance = 0;
  long split_records = 0;
  // the owned particles' balance: most owned over their mean
  auto imbalance = [&]
  {
    const auto owned = double(ranks.particles().n_owned());
    return dealii::Utilities::MPI::max(owned, comm) * n_ranks /
           dealii::Utilities::MPI::sum(owned, comm);
  };
  const double imbalance_at_start = imbalance();
  for (long n = 1; n <= steps; ++n)
  {
    const bool record = n % record_every == 0;
    one.step(record);
    ranks.step(record);
    if (!record)
      continue;
    const auto& e = ranks.energy();
    const auto& s = one.energy();
    worst_energy = std::max(worst_energy, energy_difference(e, s));
    worst_balance = std::max(worst_balance, std::abs(e.relative_error() - s.relative_error()));
    split_records += bonds_across() > 0;
  }
  const double flown =
      (serial.particles.position[0] - serial.particles.reference_position[0]).norm();
  ranks.gather(true);

  const auto& p = ranks.particles();
  long booked = 0, intact = 0;
  double constants = 0; // rest lengths of the bonds booked here, against the model's
  for (std::size_t k = 0; k < p.bonds().size(); ++k)
    if (std::size_t(p.bonds().a[k]) < p.n_owned())
    {
      ++booked;
      intact += p.bonds().state[k] == dem::BondState::intact;
      constants += p.bonds().rest_length[k];
    }
  booked = dealii::Utilities::MPI::sum(booked, comm);
  intact = dealii::Utilities::MPI::sum(intact, comm);
  constants = dealii::Utilities::MPI::sum(constants, comm);
  double model_constants = 0;
  for (const double l : serial.bonds.rest_length)
    model_constants += l;
  const long migrations = ranks.n_migrations();
  const long arrived = dealii::Utilities::MPI::sum(p.n_arrived(), comm);
  const double imbalance_at_end = imbalance();
  const auto [before_repartition, after_repartition] = ranks.particles().repartition_imbalance();
  if (root)
    std::cout << n_ranks << " ranks: " << serial.particles.size() << " particles, "
              << serial.bonds.size() << " bonds, flown " << flown << " m, " << migrations
              << " migrations, " << across << " bonds across ranks at the start, " << arrived
              << " particles changed ranks; owned particles' imbalance (most / mean) "
              << imbalance_at_start << " at the start, " << ranks.particles().n_repartitions()
              << " repartitions, up to " << before_repartition << " before one, up to "
              << after_repartition << " after one, " << imbalance_at_end << " at the end"
              << std::endl;
  check(booked_at_start == long(serial.bonds.size()) && booked == long(serial.bonds.size()),
        "bonds booked over the ranks: " + std::to_string(booked_at_start) + " at the start, " +
            std::to_string(booked) + " at the end, model " + std::to_string(serial.bonds.size()));
  check(intact == booked, "every bond intact");
  check(std::abs(constants - model_constants) <= 1e-12 * model_constants,
        "the bonds' rest lengths as formed (sum, relative " + relative(constants, model_constants) +
            ")");
  check(migrations >= 3, "migrations while flying: " + std::to_string(migrations));
  if (n_ranks > 1)
  {
    check(across > 0 && arrived > 0, "bonds across ranks, particles changing ranks");
    const double limit = distributed::DistributedParticles::max_imbalance;
    check(ranks.particles().n_repartitions() >= 1 && before_repartition > limit &&
              (!balanced || after_repartition <= limit),
          "the mesh repartitioned as the cluster flew into a rank's cells: " +
              std::to_string(ranks.particles().n_repartitions()) + " times, owned particles " +
              "most / mean up to " + figure(before_repartition) + " before, up to " +
              figure(after_repartition) + " after (limit " + figure(limit) +
              (balanced ? ")" : ", not asserted: a few particles a rank)"));
  }
  else
    check(ranks.particles().n_repartitions() == 0, "no repartition on one rank");

  // each term to 1e-10 of the largest (the flight's kinetic energy), at every record
  const auto& s = one.energy();
  check(worst_energy <= 1e-10, "every energy term (kinetic, strain, damping, initial and "
                               "the rest) as on one rank at every record: largest difference " +
                                   figure(worst_energy) + " of the largest term");
  if (n_ranks > 1)
    check(split_records >= 5, "records with bonds across ranks: " + std::to_string(split_records) +
                                  " of " + std::to_string(steps / record_every));
  // a bond lost or counted twice would change the strain energy by some 1e-2 of itself
  check(s.strain > 1e-6 * s.largest() && s.damping > 1e-6 * s.largest(),
        "strain energy " + figure(s.strain / s.largest()) + ", damping " +
            figure(s.damping / s.largest()) + " of the largest term: the check sees a bond");
  check(worst_balance <= 1e-12,
        "energy balance error as on one rank at every record (largest difference " +
            figure(worst_balance) + "; at the end " + figure(s.relative_error()) + ")");
  if (root)
  {
    double worst = 0;
    for (std::size_t i = 0; i < serial.particles.size(); ++i)
      worst = std::max(worst, (model.particles.position[i] - serial.particles.position[i]).norm());
    check(worst <= 1e-10 * flown, "positions as on one rank (largest difference " +
                                      figure(worst / flown) + " of the flight)");
  }
  return dealii::Utilities::MPI::max(failures, comm) > 0 ? 1 : 0;
}
} // namespace dembridge::distributed_check
