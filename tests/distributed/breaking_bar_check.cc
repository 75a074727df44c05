// distributed_check (distributed_check.cc, under mpirun on 1, 2 and 3 ranks):
//   distributed_check breaking_bar
// An HCP bar (r = 2.5 mm) with brittle bonds of scattered strength is pulled apart fast at one
// end; bonds break along it, some with their ends on two ranks. Against the same model on one
// rank: the crack log is the same (every crack once: time, particles, mode, to 1e-10 its energy
// and midpoint), the fracture and other energy terms agree to 1e-10 of the largest term, and on
// every rank the two copies of a bond held by two ranks agree bit for bit (state, damage,
// released energy), so a bond that breaks across ranks breaks on both, in the same step.
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
    worst_energy = std::max(worst_energy, energy_difference(ranks.energy(), one.energy()));
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
  check(worst_energy <= 1e-10, "every energy term (kinetic to fracture, contacts, walls, "
                               "initial) as on one rank at every record: largest difference " +
                                   figure(worst_energy) + " of the largest term");
  check(one.energy().fracture > 1e-3 * one.energy().largest(),
        "fracture energy " + figure(one.energy().fracture / one.energy().largest()) +
            " of the largest term");
  return dealii::Utilities::MPI::max(failures, comm) > 0 ? 1 : 0;
}
} // namespace dembridge::distributed_check
