#pragma once
// Post-failure contacts and rigid walls as one step contribution (solvers/step_contribution.h).
//
// Each step, at t_n:
//   1. the Verlet list (neighbour_list.h) and the wall lists are rebuilt if some particle moved
//      more than half the skin, or a wall moved more than half the skin along its normal, since
//      the last build; the springs of the contacts that persist are carried over;
//   2. every listed pair without an intact bond (never bonded, or broken: BondStore::state) whose
//      spheres overlap, and every sphere that overlaps a wall, gets the contact force of the
//      chosen law (contact_kernel.h: linear_spring_dashpot.h or hertz_mindlin.h, with Coulomb
//      friction and optional rolling resistance); a pair across a smooth joint's plane
//      (BondStore::sliding_joints) gets the unbonded joint's force instead (joint_contact.h:
//      along the plane's normal, sliding on it with the joint's friction), never the spheres'
//      (its spring is the pair's history). The law is a template parameter chosen once per
//      step: no virtual call and no branch on the law per contact.
// Energy (dem/core/energy.h), booked so that the leapfrog balance closes:
//   contact_strain   springs' stored energy at x^n (recording steps);
//   friction         slip of the tangential and rolling springs (tangential_spring.h), and a
//                    sliding joint's springs as they leave or come within reach (joint_contact.h);
//   contact_damping  dashpot work d^n . (v^{n-1/2} + v^{n+1/2}) / 2 dt, as the bond dashpots;
//   wall_work        work of the moving walls, 1/2 (F^{n-1} + F^n) . (u_w^n - u_w^{n-1}), F the
//                    walls' force on the particles;
//   fracture         less the stored energy of contacts that broken bonds hand over already
//                    overlapping (activation_energy): that part of the bond's energy stays.
// A wall's force (force_on_wall) is the sum of the forces the particles exert on it.
// On several MPI ranks (distributed/, contact_ranks.cc) each rank holds one ContactForces over
// its own particles and its ghosts: a pair with a ghost end is computed on both ranks, each
// applying its own particle's force, in the orientation of the particles' global ids (lower id
// first, as on one rank) so that both copies agree bit for bit; what it books (energies, the
// contact count) is booked on the rank that owns the lower id. A sphere-wall contact is the
// rank's that owns the sphere. The histories travel by global ids (export_history,
// distribute) when the particles change ranks.
#include "dem/contacts/contact_config.h"
#include "dem/contacts/contact_monitor.h"
#include "dem/contacts/hertz_mindlin.h"
#include "dem/contacts/linear_spring_dashpot.h"
#include "dem/contacts/neighbour_list.h"
#include "dem/contacts/rolling_resistance.h"
#include "dem/contacts/wall.h"
#include "dem/solvers/step_contribution.h"
#include <array>
#include <limits>
#include <vector>

namespace dembridge::dem
{
struct BondStore;

class ContactForces : public StepContribution
{
public:
  /// Validates the material and the walls (InputError naming Contacts/... or Wall NAME/...).
  ContactForces(const ContactConfig& material, const std::vector<WallConfig>& walls);

  void attach(const ParticleStore& p, const BondStore& bonds) override;
  void add_forces(ParticleStore& p, double time, double dt, bool record) override;
  void after_update(const ParticleStore& p, double time, double dt, bool record) override;
  void add_energy(EnergyBalance& e) const override;
  /// Stability limit of the contacts' springs (see contact_forces.cc).
  double critical_time_step(const ParticleStore& p) const override;
  /// Checkpoints (contact_state.cc): the Verlet list, every contact's springs, the wall
  /// candidates, the energy sums, the monitor and the platens' peak.
  bool checkpointable() const override { return true; }
  void visit_state(StateArchive& a) override;

  // Several MPI ranks (contact_ranks.cc)
  /// The rank's particles were renumbered: [0, owned) are its own, the rest ghosts, with
  /// global ids @p global_ids (kept by reference); the contacts restart from @p history
  /// (export_history's records of every rank that held them), taken by the pairs and wall
  /// contacts found at the next list build. Call before the solver attaches this.
  /// The Verlet skin from every particle (not only a rank's): the same search on every rank.
  void fix_skin(const ParticleStore& whole);
  void distribute(std::size_t owned, const std::vector<std::int64_t>& global_ids,
                  const std::vector<double>& history);
  /// Appends the history of each touching contact held here: (lower id, upper id, xi, theta,
  /// kt, kr) for a pair, (-1 - wall, id, ...) for a sphere-wall contact.
  void export_history(std::vector<double>& out) const;
  static constexpr std::size_t history_record_size = 10;
  /// The figures a run on several ranks sums over them at a record: active contacts, contact
  /// updates, list builds, search and contact seconds, activation energy, each wall's force.
  std::size_t n_figures() const { return 6 + 3 * walls_.size(); }
  void figures(double* out) const;
  /// The reporting copy (never stepped) takes the summed figures at time t (the platens'
  /// stress, strain and peak from the summed wall forces).
  void set_figures(const double* sums, double time);

  const ContactConfig& material() const { return material_; }
  /// Contacts (pairs and sphere-wall) that touched at the last step.
  std::size_t active_contacts() const { return n_active_; }
  std::size_t walls() const { return walls_.size(); }
  const Wall& wall(std::size_t w) const { return walls_[w]; }
  /// Force the particles exerted on wall w at the last step (N).
  const Vec3& force_on_wall(std::size_t w) const { return wall_force_[w]; }
  const ContactMonitor& monitor() const { return monitor_; }
  /// Stored energy of the contacts that a broken bond handed over already overlapping, at their
  /// first step (J): energy the break did not release.
  double activation_energy() const { return activation_; }
  /// The sliding joints' share of the friction term since this object was built (J): their
  /// slip, and the energy their springs hold on leaving reach less what they hold on coming
  /// within it (joint_contact.h).
  double joint_friction() const { return joint_friction_; }
  /// Measures the stress-strain curve between walls `lower` and `upper` (facing each other) on
  /// a specimen of cross-section `area` (m^2); InputError names Contacts/platens.
  void measure_platens(int lower, int upper, double area);
  const PlatenTest& platens() const { return platens_; }

  // Throughput and cost of the neighbour search (benchmarks)
  long list_builds() const { return reported_builds_ >= 0 ? reported_builds_ : list_.builds(); }
  std::size_t listed_pairs() const { return list_.size(); }
  double search_seconds() const { return search_seconds_; }
  /// Wall time in the contact force loops (pairs and walls), s.
  double contact_seconds() const { return contact_seconds_; }
  long contact_updates() const { return contact_updates_; }

private:
  template <class Law, bool rolling, bool damping, bool record>
  void compute(ParticleStore& p, double time, double dt);
  void rebuild(const ParticleStore& p, double time);
  void update_monitor(const ParticleStore& p, double time, double dt);
  void update_platens(double time);
  /// After a list build following distribute(): the new pairs and wall contacts take their
  /// history from the records given there.
  void take_distributed_history();
  /// The bond joining each listed pair (pair_bond_), from the bonds of each particle, and
  /// whether the pair lies across a sliding joint's plane (pair_joint_).
  void link_pairs_to_bonds();

  ContactConfig material_;
  std::vector<Wall> walls_;
  LinearSpringDashpot linear_pair_, linear_wall_;
  HertzMindlin hertz_pair_, hertz_wall_;
  RollingResistance rolling_;
  bool damping_ = false;

  const BondStore* bonds_ = nullptr;
  // several ranks: particles [0, owned_) are this rank's; pairs oriented by global id
  std::size_t owned_ = std::numeric_limits<std::size_t>::max();
  const std::vector<std::int64_t>* global_id_ = nullptr;
  std::vector<double> history_in_; ///< records from distribute()
  std::vector<std::pair<std::array<std::int64_t, 2>, std::size_t>> history_key_; ///< sorted
  long reported_builds_ = -1;
  // bonds of each particle (CSR): partner and bond index
  std::vector<std::int32_t> bond_start_, bond_partner_, bond_index_;

  // particle pairs: the Verlet list and beside it, per pair, the bond joining it (or -1) and
  // the contact history
  NeighbourList list_;
  std::vector<std::int32_t> pair_bond_;
  /// 1: across a sliding joint's plane, 2: across a sliding grain boundary, 0: neither (empty
  /// without sliding joints)
  std::vector<std::uint8_t> pair_joint_;
  std::vector<long> joint_side_;          ///< per particle: SlidingJoints::side at X (or empty)
  std::vector<std::int32_t> joint_grain_; ///< per particle: its grain, with sliding boundaries
  std::vector<Vec3> xi_, theta_, xi_old_, theta_old_;
  std::vector<double> kt_, kr_, kt_old_, kr_old_; ///< spring stiffnesses at the last step; 0: apart

  // sphere-wall candidates, sorted by (wall, particle), with their history
  std::vector<std::int32_t> wall_of_, wall_particle_, wall_of_old_, wall_particle_old_;
  std::vector<Vec3> wall_xi_, wall_theta_, wall_xi_old_, wall_theta_old_;
  std::vector<double> wall_kt_, wall_kr_, wall_kt_old_, wall_kr_old_;
  std::vector<double> wall_offset_built_; ///< point . normal at the last build

  // per step
  std::vector<Vec3> wall_force_, wall_force_prev_, wall_damping_force_;
  std::vector<Vec3> point_now_;                      ///< wall points at t_n
  std::vector<Vec3> damping_force_, damping_torque_; ///< dashpot resultants per particle
  std::size_t n_active_ = 0;

  // energy
  double stored_ = 0, slip_ = 0, damping_work_ = 0, damping_lead_ = 0, wall_work_ = 0;
  double activation_ = 0, joint_friction_ = 0;
  mutable double activation_booked_ = 0; ///< part of activation_ already moved out of fracture

  ContactMonitor monitor_;
  PlatenTest platens_;
  double search_seconds_ = 0, contact_seconds_ = 0;
  long contact_updates_ = 0;
};
} // namespace dembridge::dem
