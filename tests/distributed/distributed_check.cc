// Checks of the distributed particle layer (distributed/), run under mpirun on 1, 2 and 3 ranks:
//   distributed_check flying_cluster
// A bonded HCP cluster, spinning and vibrating, flies along x across the background mesh: its
// particles change cells and ranks many times (the check asserts migrations, particles changing
// ranks and bonds across ranks at several records). Against the same model stepped on one rank by
// dem/'s ExplicitSolver:
//  - every bond survives with its state: the bonds booked over the ranks are the model's, all
//    intact, and their constants as formed;
//  - at every record (each 200 steps) the energy terms (kinetic, strain, bond dashpots' damping,
//    initial) agree to 1e-10 of the largest term, and the energy balance error to 1e-12
//    (absolute, of a relative error);
//  - every particle's final position agrees to 1e-10 of the distance flown;
//  - on several ranks the mesh is repartitioned (the cluster flies into a rank's cells).
//   distributed_check repartitioned_cluster
// The same with r = 2.5 mm (718 particles, 2000 steps): besides, the repartitions start from an
// imbalance (most owned particles over their mean) above DistributedParticles::max_imbalance and
// each leaves it at most that (with 68 particles p4est's cell families are too coarse for it).
//   distributed_check breaking_bar
// An HCP bar (r = 2.5 mm) with brittle bonds of scattered strength is pulled apart fast at one
// end; bonds break along it, some with their ends on two ranks. Against the same model on one
// rank: the crack log is the same (every crack once: time, particles, mode, to 1e-10 its energy
// and midpoint), the fracture and other energy terms agree to 1e-10 of the largest term, and on
// every rank the two copies of a bond held by two ranks agree bit for bit (state, damage,
// released energy), so a bond that breaks across ranks breaks on both, in the same step.
//   distributed_check shattering_cluster
// The flying cluster's packing with brittle bonds, its octants thrown apart: it breaks into
// fragments that fly apart across the ranks, so that broken bonds join particles
// that are no longer in each other's ghost layer (DistributedParticles::detached_bonds). Against
// the same model on one rank, the ranks' bond pieces of the ParaView bond files (bond_piece.h)
// hold every bond of the model exactly once (by its id, the model's index), in its one-rank
// state (intact / broken), between the same two particles (user ids) at the same places (to
// 1e-10 of the largest distance flown).
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
// Exit code 0 on success; a failed check prints one line on rank 0 and returns 1.
#include "dem/bonds/bonding.h"
#include "dem/contacts/contact_forces.h"
#include "dem/model/model.h"
#include "dem/packing/packings.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/time_step.h"
#include "distributed/bond_piece.h"
#include "distributed/bond_records.h"
#include "distributed/distributed_solver.h"
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deal.II/base/mpi.h>
#include <iostream>
#include <map>
#include <random>
#include <string>

using namespace dembridge;
using dem::Vec3;

namespace
{
int failures = 0;
bool root = false;

void check(bool ok, const std::string& what)
{
  if (!ok)
  {
    ++failures;
    if (root)
      std::cout << "FAILED: " << what << std::endl;
  }
  else if (root)
    std::cout << "ok: " << what << std::endl;
}

std::string figure(double x)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

std::string relative(double a, double b)
{
  return figure(std::abs(a - b) / std::max(std::abs(b), 1e-300));
}

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
    for (const auto& [a, b] : {std::pair(e.kinetic, s.kinetic), std::pair(e.strain, s.strain),
                               std::pair(e.damping, s.damping), std::pair(e.initial, s.initial)})
      worst_energy = std::max(worst_energy, std::abs(a - b) / s.largest());
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
  check(worst_energy <= 1e-10, "energy terms (kinetic, strain, damping, initial) as on one "
                               "rank at every record: largest difference " +
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

/// The flying cluster's packing, bonds (E_b = 4 GPa) of 1.5 MPa tensile and 3 MPa shear
/// strength (normal scatter 0.3), its eight octants (split at the centre) thrown apart at
/// 3 m/s along each axis, with seeded random velocities of 0.1 m/s and angular
/// velocities of 10 rad/s (standard deviations) on top: the bonds between the octants break.
dem::Model shattering_cluster()
{
  dem::CaseConfig c;
  c.particles.kind = dem::ParticleSource::Kind::hcp;
  c.particles.radius = 5e-3;
  c.particles.box_size = Vec3(0.05, 0.04, 0.04);
  c.bonds.material.youngs_modulus = 4e9;
  c.damage.law.mode = dem::FailureMode::brittle;
  c.damage.tensile_strength = 1.5e6;
  c.damage.shear_strength = 3e6;
  c.damage.scatter = dem::StrengthScatter::normal;
  c.damage.scatter_deviation = 0.3;
  c.run.bond_force_records = false;
  dem::Model m = dem::build_model(c);
  Vec3 centre = Vec3::Zero();
  for (const Vec3& x : m.particles.position)
    centre += x / double(m.particles.size());
  std::mt19937 rng(11);
  std::normal_distribution<double> n01(0, 1);
  for (std::size_t i = 0; i < m.particles.size(); ++i)
  {
    const Vec3 d = m.particles.position[i] - centre;
    m.particles.velocity[i] = Vec3(d.x() > 0 ? 3 : -3, d.y() > 0 ? 3 : -3, d.z() > 0 ? 3 : -3) +
                              0.1 * Vec3(n01(rng), n01(rng), n01(rng));
    m.particles.angular_velocity[i] = 10 * Vec3(n01(rng), n01(rng), n01(rng));
  }
  return m;
}

int shattering_cluster_check(MPI_Comm comm)
{
  const long steps = 8000;
  dem::Model serial = shattering_cluster(), model = shattering_cluster();
  const double width = 1.25 * 2 * 5e-3; // cells the cut-off wide: fragments leave them soon
  const distributed::BackgroundGrid grid =
      distributed::make_background_grid(Vec3(-0.15, -0.15, -0.15), Vec3(0.2, 0.19, 0.19), width);
  dem::ExplicitSolver one(serial.particles, serial.bonds, {}, {}, {}, {serial.time_step});
  distributed::DistributedSolver ranks(model, {model.time_step}, comm, &grid);
  for (long n = 1; n <= steps; ++n)
  {
    one.step(n == steps);
    ranks.step(n == steps);
  }
  double flown = 0;
  for (std::size_t i = 0; i < serial.particles.size(); ++i)
    flown = std::max(
        flown, (serial.particles.position[i] - serial.particles.reference_position[i]).norm());
  // every rank's piece: per bond its id, state, its ends' user ids and positions
  const distributed::BondPiece piece = distributed::bond_piece(ranks.particles());
  std::vector<double> mine;
  for (std::size_t k = 0; k < piece.bonds.size(); ++k)
  {
    const auto a = std::size_t(piece.bonds.a[k]), b = std::size_t(piece.bonds.b[k]);
    mine.insert(mine.end(), {double(piece.ids[k]), double(piece.bonds.state[k]),
                             double(piece.ends.id[a]), double(piece.ends.id[b])});
    for (const std::size_t i : {a, b})
      mine.insert(mine.end(), piece.ends.position[i].data(), piece.ends.position[i].data() + 3);
  }
  const auto pieces = dealii::Utilities::MPI::gather(comm, mine, 0);
  const auto& particles = ranks.particles();
  const long repartitions = particles.n_repartitions();
  const long detached = dealii::Utilities::MPI::sum(
      long(particles.detached_bonds().size() / distributed::bond_record_size(particles.bonds())),
      comm);
  if (root)
  {
    const dem::BondStore& b = serial.bonds;
    const dem::ParticleStore& p = serial.particles;
    std::vector<int> seen(b.size(), 0);
    long wrong_state = 0, wrong_ends = 0, broken = 0;
    double worst = 0;
    for (const auto& rank : pieces)
      for (std::size_t at = 0; at < rank.size(); at += 10)
      {
        const double* r = &rank[at];
        const auto k = std::size_t(r[0]);
        if (k >= b.size() || seen[k]++)
          continue;
        wrong_state += int(r[1]) != int(b.state[k]);
        broken += b.state[k] == dem::BondState::broken;
        const auto ia = std::size_t(b.a[k]), ib = std::size_t(b.b[k]);
        wrong_ends += int(r[2]) != p.id[ia] || int(r[3]) != p.id[ib];
        worst = std::max({worst, (Vec3(r[4], r[5], r[6]) - p.position[ia]).norm(),
                          (Vec3(r[7], r[8], r[9]) - p.position[ib]).norm()});
      }
    const long once = std::count(seen.begin(), seen.end(), 1);
    std::cout << b.size() << " bonds, " << broken << " broken, " << repartitions
              << " repartitions, " << detached
              << " broken bonds with their far end out of the rank's store; flown " << flown << " m"
              << std::endl;
    check(once == long(b.size()) && std::count(seen.begin(), seen.end(), 0) == 0,
          "every bond in the pieces exactly once (" + std::to_string(once) + " of " +
              std::to_string(b.size()) + ")");
    check(wrong_state == 0, "the bonds' states as on one rank (" + std::to_string(wrong_state) +
                                " differ; " + std::to_string(broken) + " broken)");
    check(broken > 0 && broken < long(b.size()), "the cluster breaks: bonds broken and intact");
    check(wrong_ends == 0 && worst <= 1e-10 * flown,
          "the bonds' ends as on one rank (particles; places to " + figure(worst / flown) +
              " of the distance flown)");
    if (dealii::Utilities::MPI::n_mpi_processes(comm) > 1)
      check(detached > 0, "broken bonds whose ends flew out of each other's ghost layers");
    // on 3 ranks the fragments imbalance the ranks: detached bonds travel through repartitions
    if (dealii::Utilities::MPI::n_mpi_processes(comm) == 3)
      check(repartitions >= 1, "repartitions: " + std::to_string(repartitions));
  }
  return dealii::Utilities::MPI::max(failures, comm) > 0 ? 1 : 0;
}

/// The pulled bar: 0.08 x 0.015 x 0.015 m of HCP spheres, parallel bonds (E_b = 4 GPa) of
/// normal scatter 0.3 around 1 MPa tensile and 2 MPa shear strength, bond dashpots (xi = 0.05);
/// the x- face held in x, the x+ face pulled at 0.5 m/s after a 0.1 ms ramp.
dem::Model breaking_bar()
{
  dem::CaseConfig c;
  c.particles.kind = dem::ParticleSource::Kind::hcp;
  c.particles.radius = 2.5e-3;
  c.particles.box_size = Vec3(0.08, 0.015, 0.015);
  c.bonds.material.model = dem::BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.stiffness_ratio = 4.2;
  c.damage.law.mode = dem::FailureMode::brittle;
  c.damage.tensile_strength = 1e6;
  c.damage.shear_strength = 2e6;
  c.damage.scatter = dem::StrengthScatter::normal;
  c.damage.scatter_deviation = 0.3;
  c.run.bond_damping_ratio = 0.05;
  c.run.bond_force_records = false;
  dem::GroupConfig fixed, pulled;
  fixed.name = "fixed", pulled.name = "pulled";
  fixed.selection.kind = pulled.selection.kind = dem::GroupSelection::Kind::face;
  fixed.selection.face_axis = pulled.selection.face_axis = 0;
  pulled.selection.face_upper = true;
  fixed.fixed = dem::dof_ux;
  c.groups = {fixed, pulled};
  dem::LoadConfig pull;
  pull.group = "pulled";
  pull.load.name = "pull";
  pull.load.kind = dem::LoadKind::velocity;
  pull.load.value = Vec3(0.5, 0, 0);
  pull.load.components = 1;
  pull.load.ramp_time = 1e-4;
  c.loads = {pull};
  return dem::build_model(c);
}

int breaking_bar_check(MPI_Comm comm)
{
  const unsigned n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const long steps = 3000, record_every = 100;
  dem::Model serial = breaking_bar(), model = breaking_bar();
  dem::ExplicitSolver one(serial.particles, serial.bonds, serial.groups, serial.constraints,
                          serial.loads, {serial.time_step});
  distributed::DistributedSolver ranks(model, {model.time_step}, comm);
  double worst_energy = 0;
  for (long n = 1; n <= steps; ++n)
  {
    const bool record = n % record_every == 0;
    one.step(record);
    ranks.step(record);
    if (!record)
      continue;
    const auto &e = ranks.energy(), &s = one.energy();
    for (const auto& [a, b] : {std::pair(e.kinetic, s.kinetic), std::pair(e.strain, s.strain),
                               std::pair(e.damping, s.damping), std::pair(e.external, s.external),
                               std::pair(e.fracture, s.fracture)})
      worst_energy = std::max(worst_energy, std::abs(a - b) / s.largest());
  }
  ranks.gather(true);

  // every copy of every bond, gathered on rank 0: ids, state, damage, released energy
  const auto& p = ranks.particles();
  std::vector<double> mine;
  for (std::size_t k = 0; k < p.bonds().size(); ++k)
    mine.insert(mine.end(),
                {double(p.global_ids()[std::size_t(p.bonds().a[k])]),
                 double(p.global_ids()[std::size_t(p.bonds().b[k])]), double(p.bonds().state[k]),
                 p.bonds().damage[k], p.bonds().dissipated[k]});
  std::vector<double> owners;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    owners.push_back(double(p.global_ids()[i]));
  const auto copies = dealii::Utilities::MPI::gather(comm, mine, 0);
  const auto owned = dealii::Utilities::MPI::gather(comm, owners, 0);
  const long cracks = ranks.n_broken_bonds();
  if (root)
  {
    std::map<std::pair<long, long>, std::vector<const double*>> by_pair;
    for (const auto& rank : copies)
      for (std::size_t at = 0; at < rank.size(); at += 5)
        by_pair[{long(rank[at]), long(rank[at + 1])}].push_back(&rank[at]);
    long twice = 0, disagree = 0, broken_twice = 0;
    for (const auto& [pair, list] : by_pair)
    {
      twice += list.size() == 2;
      broken_twice += list.size() == 2 && list[0][2] == double(dem::BondState::broken);
      for (const double* copy : list)
        disagree += std::memcmp(copy, list[0], 5 * sizeof(double)) != 0;
    }
    std::vector<int> owner(serial.particles.size(), -1);
    for (std::size_t r = 0; r < owned.size(); ++r)
      for (const double id : owned[r])
        owner[std::size_t(id)] = int(r);
    std::vector<long> global_of_user(serial.particles.size());
    for (std::size_t i = 0; i < serial.particles.size(); ++i)
      global_of_user[std::size_t(model.particles.id[i])] = long(i);
    const auto& mine_log = ranks.report()->cracks();
    const auto& one_log = one.cracks();
    long across = 0, same = 0;
    for (std::size_t c = 0; c < std::min(mine_log.size(), one_log.size()); ++c)
    {
      const auto &x = mine_log[c], &y = one_log[c];
      same += x.time == y.time && x.a == y.a && x.b == y.b && x.mode == y.mode &&
              std::abs(x.energy - y.energy) <= 1e-10 * std::abs(y.energy) &&
              (x.midpoint - y.midpoint).norm() <= 1e-10 * 0.08;
      across += owner[std::size_t(global_of_user[std::size_t(x.a)])] !=
                owner[std::size_t(global_of_user[std::size_t(x.b)])];
    }
    std::cout << n_ranks << " ranks: " << serial.particles.size() << " particles, "
              << serial.bonds.size() << " bonds, " << one_log.size() << " cracks on one rank, "
              << cracks << " here, " << across << " of them between particles of two ranks; "
              << twice << " bonds held by two ranks, " << broken_twice << " of them broken"
              << std::endl;
    check(one_log.size() >= 20, "the bar cracks: " + std::to_string(one_log.size()) + " bonds");
    check(long(mine_log.size()) == cracks && cracks == long(one_log.size()) &&
              same == long(one_log.size()),
          "the crack log as on one rank, every crack once (" + std::to_string(same) + " of " +
              std::to_string(one_log.size()) + " equal)");
    check(disagree == 0, "the copies of the bonds held by two ranks agree bit for bit (" +
                             std::to_string(disagree) + " differ)");
    if (n_ranks > 1)
      check(across > 0 && broken_twice > 0, "bonds broken across ranks");
  }
  check(worst_energy <= 1e-10, "energy terms (kinetic, strain, damping, external, fracture) as "
                               "on one rank at every record: largest difference " +
                                   figure(worst_energy) + " of the largest term");
  check(one.energy().fracture > 1e-3 * one.energy().largest(),
        "fracture energy " + figure(one.energy().fracture / one.energy().largest()) +
            " of the largest term");
  return dealii::Utilities::MPI::max(failures, comm) > 0 ? 1 : 0;
}

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
    for (const auto& [x, y] :
         {std::pair(e.kinetic, s.kinetic), std::pair(e.strain, s.strain),
          std::pair(e.damping, s.damping), std::pair(e.external, s.external),
          std::pair(e.contact_strain, s.contact_strain), std::pair(e.friction, s.friction),
          std::pair(e.contact_damping, s.contact_damping), std::pair(e.wall_work, s.wall_work),
          std::pair(e.initial, s.initial)})
      worst_energy = std::max(worst_energy, std::abs(x - y) / s.largest());
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
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const std::string name = argc > 1 ? argv[1] : "";
  try
  {
    if (name == "flying_cluster")
      return flying_cluster_check(MPI_COMM_WORLD, 5e-3, 4000, false);
    if (name == "repartitioned_cluster")
      return flying_cluster_check(MPI_COMM_WORLD, 2.5e-3, 2000, true);
    if (name == "breaking_bar")
      return breaking_bar_check(MPI_COMM_WORLD);
    if (name == "colliding_clusters")
      return colliding_clusters_check(MPI_COMM_WORLD);
    if (name == "shattering_cluster")
      return shattering_cluster_check(MPI_COMM_WORLD);
    if (root)
      std::cerr << "usage: distributed_check flying_cluster | repartitioned_cluster | breaking_bar "
                   "| colliding_clusters | "
                   "shattering_cluster"
                << std::endl;
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "distributed_check: " << e.what() << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  return 1;
}
