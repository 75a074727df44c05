// distributed_check (distributed_check.cc, under mpirun on 1, 2 and 3 ranks):
//   distributed_check colliding_clusters
// Two bonded HCP clusters (r = 2.5 mm, bond dashpots) with contacts (linear law, friction,
// restitution, rolling resistance) and a floor wall that moves: cluster A is pressed onto the
// floor and slides on it, cluster B lies on A and slides the other way. Their contacts join
// particles of two ranks at times, and contacts travel with their particles through migrations.
// Against the same model on one rank:
//  - at every record the energy terms (kinetic, strain, damping, external work, contact strain,
//    friction, contact damping, wall work, initial) agree to 1e-10 of the largest term, the
//    energy balance error to 1e-12 (absolute, of a relative error), the contact count exactly
//    and the floor's force to 1e-9 of its largest value (a contact force is k delta with delta
//    a micrometre: positions that differ by 1e-14 m, sums taken in another order, move it by
//    1e-8 of itself);
//  - every particle's final position agrees to 1e-10 of the distance flown;
//  - background cells narrower than 1.25 contact cut-offs (2 R) are refused.
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

/// Cluster A (0.03 x 0.02 x 0.02 m of HCP spheres, r = 2.5 mm, E_b = 4 GPa, bond dashpots
/// xi = 0.05) on the floor wall z = 0, which moves back at 2 m/s, sliding at 3 m/s along x;
/// cluster B, the same, lying on A (10 mm ahead, touching it) and sliding back at 3 m/s;
/// each pressed down by 20 N. Linear contacts: k_n = 2e6 N/m, e = 0.5,
/// mu = 0.5, mu_r = 0.05.
dem::Model colliding_clusters()
{
  dem::Model m;
  dem::ParticleSource src;
  src.kind = dem::ParticleSource::Kind::hcp;
  src.radius = 2.5e-3;
  src.box_size = Vec3(0.03, 0.02, 0.02);
  dem::ParticleStore a, b;
  dem::generate_particles(src, a);
  dem::generate_particles(src, b);
  double z_min = 1e300, z_max = -1e300;
  for (const Vec3& x : a.position)
    z_min = std::min(z_min, x[2] - src.radius), z_max = std::max(z_max, x[2] + src.radius);
  const std::size_t n = a.size();
  dem::ParticleStore& p = m.particles;
  p = a;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3 shift = Vec3(0.01, 0.002, z_max - z_min); // touching A
    p.position.push_back(b.position[i] + shift);
    p.reference_position.push_back(b.reference_position[i] + shift);
    p.velocity.push_back(b.velocity[i]), p.angular_velocity.push_back(b.angular_velocity[i]);
    p.orientation.push_back(b.orientation[i]), p.force.push_back(b.force[i]);
    p.torque.push_back(b.torque[i]), p.radius.push_back(b.radius[i]), p.mass.push_back(b.mass[i]);
    p.inertia.push_back(b.inertia[i]), p.dof_mask.push_back(b.dof_mask[i]);
    p.group_mask.push_back(b.group_mask[i]), p.coordination.push_back(b.coordination[i]);
    p.id.push_back(int(n + i));
  }
  for (std::size_t i = 0; i < 2 * n; ++i)
  {
    p.position[i][2] -= z_min, p.reference_position[i][2] -= z_min;
    p.velocity[i] = i < n ? Vec3(3, 0, 0) : Vec3(-3, 0, 0);
  }
  dem::BondMaterial mat;
  mat.youngs_modulus = 4e9;
  dem::form_bonds(p, m.bonds, mat, 1.0);
  dem::assign_bond_damping(p, m.bonds, 0.05);
  dem::Group cluster_a;
  cluster_a.name = "a";
  for (std::size_t i = 0; i < n; ++i)
    cluster_a.members.push_back(int(i));
  dem::Group cluster_b;
  cluster_b.name = "b";
  for (std::size_t i = n; i < 2 * n; ++i)
    cluster_b.members.push_back(int(i));
  m.groups = {cluster_a, cluster_b};
  dem::Load press, push;
  press.name = "press", press.group = 0, press.value = Vec3(0, 0, -20);
  push.name = "push", push.group = 1, push.value = Vec3(0, 0, -20);
  m.loads = {press, push};
  dem::ContactConfig contacts;
  contacts.model = dem::ContactModel::linear;
  contacts.normal_stiffness = 2e6;
  contacts.restitution = 0.5;
  contacts.friction = 0.5;
  contacts.rolling_friction = 0.05;
  dem::WallConfig floor;
  floor.name = "floor";
  floor.point = Vec3::Zero(), floor.normal = Vec3::UnitZ(), floor.velocity = Vec3(-2, 0, 0);
  auto forces = std::make_shared<dem::ContactForces>(contacts, std::vector{floor});
  m.critical = dem::estimate_critical_time_step(p, m.bonds);
  m.time_step = 0.5 * std::min(m.critical.critical(), forces->critical_time_step(p));
  m.contributions.push_back(forces);
  return m;
}

int colliding_clusters_check(MPI_Comm comm)
{
  const unsigned n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const long steps = 8000, record_every = 100;
  dem::Model serial = colliding_clusters(), model = colliding_clusters();
  const std::size_t n_a = serial.groups[0].members.size();
  // cells 1.5 times the contact cut-off (2 R) wide over the whole run: many migrations
  const distributed::BackgroundGrid grid = distributed::make_background_grid(
      Vec3(-0.02, -0.02, -0.02), Vec3(0.1, 0.04, 0.07), 1.5 * 2 * 2.5e-3);
  {
    // a ghost layer narrower than 1.25 contact cut-offs is refused on every rank
    dem::Model narrow_model = colliding_clusters();
    const distributed::BackgroundGrid narrow = distributed::make_background_grid(
        Vec3(-0.02, -0.02, -0.02), Vec3(0.1, 0.04, 0.07), 1.2 * 2 * 2.5e-3);
    std::string refused;
    try
    {
      distributed::DistributedSolver(narrow_model, {narrow_model.time_step}, comm, &narrow);
    }
    catch (const dem::InputError& e)
    {
      refused = e.what();
    }
    check(refused.find("not wider than 1.25 times the contact cut-off") != std::string::npos,
          "background cells narrower than 1.25 contact cut-offs refused: '" + refused + "'");
  }
  dem::ExplicitSolver one(serial.particles, serial.bonds, serial.groups, serial.constraints,
                          serial.loads, {serial.time_step});
  auto& one_contacts = *dynamic_cast<dem::ContactForces*>(serial.contributions[0].get());
  one.add_contribution(&one_contacts);
  distributed::DistributedSolver ranks(model, {model.time_step}, comm, &grid);
  const auto& ranks_contacts = *dynamic_cast<dem::ContactForces*>(model.contributions[0].get());
  // touching pairs of particles of the two clusters with their ends on two ranks (each counted
  // on the rank of its cluster-A end)
  auto touching_across = [&]
  {
    const auto& p = ranks.particles().particles();
    const auto& ids = ranks.particles().global_ids();
    const std::size_t owned = ranks.particles().n_owned();
    long count = 0;
    for (std::size_t i = 0; i < owned; ++i)
      for (std::size_t j = owned; j < p.size(); ++j)
        count += std::size_t(ids[i]) < n_a && std::size_t(ids[j]) >= n_a &&
                 (p.position[i] - p.position[j]).norm() < p.radius[i] + p.radius[j];
    return dealii::Utilities::MPI::sum(count, comm);
  };
  double worst_energy = 0, worst_balance = 0, worst_wall = 0, largest_wall = 0, stored = 0;
  long count_differs = 0, split_records = 0, most_contacts = 0, wall_records = 0;
  for (long n = 1; n <= steps; ++n)
  {
    const bool record = n % record_every == 0;
    one.step(record);
    ranks.step(record);
    if (!record)
      continue;
    const auto &e = ranks.energy(), &s = one.energy();
    worst_energy = std::max(worst_energy, energy_difference(e, s));
    worst_balance = std::max(worst_balance, std::abs(e.relative_error() - s.relative_error()));
    stored = std::max(stored, s.contact_strain / s.largest());
    const long across = touching_across();
    split_records += across > 0;
    most_contacts = std::max(most_contacts, long(one_contacts.active_contacts()));
    if (root)
    {
      count_differs += ranks_contacts.active_contacts() != one_contacts.active_contacts();
      const double fz = one_contacts.force_on_wall(0)[2];
      wall_records += fz != 0;
      largest_wall = std::max(largest_wall, std::abs(fz));
      worst_wall = std::max(worst_wall, std::abs(ranks_contacts.force_on_wall(0)[2] - fz));
    }
  }
  const double flown =
      (serial.particles.position[0] - serial.particles.reference_position[0]).norm();
  ranks.gather(true);
  const long migrations = ranks.n_migrations();
  const long arrived = dealii::Utilities::MPI::sum(ranks.particles().n_arrived(), comm);
  const auto& s = one.energy();
  if (root)
  {
    std::cout << n_ranks << " ranks: " << serial.particles.size() << " particles, "
              << serial.bonds.size() << " bonds, flown " << flown << " m, " << migrations
              << " migrations, " << ranks.particles().n_repartitions() << " repartitions, "
              << arrived << " particles changed ranks, up to " << most_contacts << " contacts, "
              << split_records << " records with contacts across ranks; energy:"
              << " kinetic " << s.kinetic << ", contact strain " << s.contact_strain
              << ", friction " << s.friction << ", contact damping " << s.contact_damping
              << ", wall work " << s.wall_work << ", balance error " << s.relative_error()
              << std::endl;
    check(count_differs == 0, "the contact count as on one rank at every record (" +
                                  std::to_string(count_differs) + " records differ)");
    check(wall_records >= 30 && worst_wall <= 1e-9 * largest_wall,
          "the floor's force as on one rank at every record: largest difference " +
              figure(worst_wall / largest_wall) + " of its largest, " +
              std::to_string(wall_records) + " records touching");
    double worst = 0;
    for (std::size_t i = 0; i < serial.particles.size(); ++i)
      worst = std::max(worst, (model.particles.position[i] - serial.particles.position[i]).norm());
    check(worst <= 1e-10 * flown, "positions as on one rank (largest difference " +
                                      figure(worst / flown) + " of the flight)");
  }
  check(worst_energy <= 1e-10,
        "energy terms (kinetic, strain, damping, external, contact strain, friction, contact "
        "damping, wall work, initial) as on one rank at every record: largest difference " +
            figure(worst_energy) + " of the largest term");
  check(worst_balance <= 1e-12, "energy balance error as on one rank at every record (largest "
                                "difference " +
                                    figure(worst_balance) + "; at the end " +
                                    figure(s.relative_error()) + ")");
  // the check sees the contacts: they hold energy, slip and damp
  check(stored > 1e-6 && s.friction > 1e-4 * s.largest() && s.contact_damping > 1e-4 * s.largest(),
        "contact strain up to " + figure(stored) + ", friction " +
            figure(s.friction / s.largest()) + ", contact damping " +
            figure(s.contact_damping / s.largest()) + " of the largest term");
  check(migrations >= 5, "migrations: " + std::to_string(migrations));
  // on 3 ranks the clusters' sliding imbalances the ranks: contacts travel through repartitions
  if (n_ranks == 3)
    check(ranks.particles().n_repartitions() >= 1,
          "repartitions: " + std::to_string(ranks.particles().n_repartitions()));
  if (n_ranks > 1)
    check(split_records >= 3 && arrived > 0,
          "records with contacts across ranks: " + std::to_string(split_records) +
              ", particles changing ranks: " + std::to_string(arrived));
  return dealii::Utilities::MPI::max(failures, comm) > 0 ? 1 : 0;
}
} // namespace dembridge::distributed_check
