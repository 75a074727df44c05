// Checkpoint state of the contacts (contact_forces.h, neighbour_list.h): what a step reads from
// the steps before it. The buffers a rebuild swaps in (the *_old arrays, the cell list) and the
// per-step dashpot resultants (zeroed after each step) are scratch and not stored; the bond of
// each listed pair is derived again from the bonds.
#include "dem/bonds/bond_store.h"
#include "dem/contacts/contact_forces.h"
#include "dem/contacts/neighbour_list.h"

namespace dembridge::dem
{
void NeighbourList::visit_state(StateArchive& a)
{
  StateGroup group(a, "neighbour_list");
  double skin = skin_;
  a.io("skin", skin);
  if (a.loading() && skin != skin_)
    throw InputError(a.where() + "skin: " + std::to_string(skin) + " m in the checkpoint, " +
                     std::to_string(skin_) + " m in this run");
  a.io("builds", builds_);
  a.io("x_built", x_built_);
  a.io("first", first_);
  a.io("second", second_);
  if (a.loading() && second_.size() != first_.size())
    throw InputError(a.where() + "second: not as long as 'first'");
}

void ContactForces::link_pairs_to_bonds()
{
  const auto& first = list_.first();
  const auto& second = list_.second();
  pair_bond_.resize(first.size());
  for (std::size_t k = 0; k < first.size(); ++k)
  {
    std::int32_t bond = -1;
    const auto i = std::size_t(first[k]);
    for (std::int32_t q = bond_start_[i]; q < bond_start_[i + 1]; ++q)
      if (bond_partner_[std::size_t(q)] == second[k])
        bond = bond_index_[std::size_t(q)];
    pair_bond_[k] = bond;
  }
  pair_joint_.assign(joint_side_.empty() ? 0 : first.size(), 0);
  for (std::size_t k = 0; k < pair_joint_.size(); ++k)
  {
    const auto i = std::size_t(first[k]), j = std::size_t(second[k]);
    pair_joint_[k] = joint_side_[i] != joint_side_[j]                              ? 1
                     : !joint_grain_.empty() && joint_grain_[i] != joint_grain_[j] ? 2
                                                                                   : 0;
  }
}

void ContactForces::visit_state(StateArchive& a)
{
  StateGroup group(a, "contacts");
  list_.visit_state(a);
  const std::size_t n_particles = bond_start_.empty() ? 0 : bond_start_.size() - 1;
  if (a.loading())
    for (const auto* ids : {&list_.first(), &list_.second()})
      for (std::int32_t i : *ids)
        if (i < 0 || std::size_t(i) >= n_particles)
          throw InputError(a.where() + "neighbour_list: particle " + std::to_string(i) +
                           " outside the model");
  {
    StateGroup pairs(a, "pairs"); // per listed pair: tangential and rolling springs
    a.io("xi", xi_);
    a.io("theta", theta_);
    a.io("kt", kt_);
    a.io("kr", kr_);
  }
  {
    StateGroup walls(a, "walls"); // sphere-wall candidates and the walls' running terms
    a.io("wall", wall_of_);
    a.io("particle", wall_particle_);
    a.io("xi", wall_xi_);
    a.io("theta", wall_theta_);
    a.io("kt", wall_kt_);
    a.io("kr", wall_kr_);
    a.io_sized("offset_built", wall_offset_built_);
    a.io_sized("force", wall_force_);
    a.io_sized("force_previous", wall_force_prev_);
    a.io_sized("damping_force", wall_damping_force_);
    a.io_sized("point", point_now_);
  }
  a.io("active", n_active_);
  {
    StateGroup energy(a, "energy");
    a.io("stored", stored_);
    a.io("slip", slip_);
    a.io("damping_work", damping_work_);
    a.io("damping_lead", damping_lead_);
    a.io("wall_work", wall_work_);
    a.io("activation", activation_);
    a.io("activation_booked", activation_booked_);
  }
  {
    StateGroup monitor(a, "monitor");
    ContactMonitor& m = monitor_;
    a.io("enabled", m.enabled);
    a.io("max_overlap", m.max_overlap);
    a.io("max_force", m.max_force);
    a.io("started", m.started);
    a.io("finished", m.finished);
    a.io("wall", m.wall);
    a.io("a", m.a);
    a.io("b", m.b);
    a.io("start_time", m.start_time);
    a.io("end_time", m.end_time);
    a.io("approach_speed", m.approach_speed);
    a.io("rebound_speed", m.rebound_speed);
    a.io("last_overlap", m.last_overlap);
  }
  {
    StateGroup platens(a, "platens");
    PlatenTest& t = platens_;
    a.io("enabled", t.enabled);
    a.io("lower", t.lower);
    a.io("upper", t.upper);
    a.io("area", t.area);
    a.io("length", t.length);
    a.io("stress", t.stress);
    a.io("strain", t.strain);
    a.io("peak_stress", t.peak_stress);
    a.io("strain_at_peak", t.strain_at_peak);
    a.io("time_at_peak", t.time_at_peak);
  }
  a.io("contact_updates", contact_updates_);
  a.io("search_seconds", search_seconds_);
  a.io("contact_seconds", contact_seconds_);
  if (!a.loading())
    return;
  const std::size_t np = list_.size(), nw = wall_of_.size();
  for (std::size_t size : {xi_.size(), theta_.size(), kt_.size(), kr_.size()})
    if (size != np)
      throw InputError(a.where() + "pairs: not one entry per listed pair");
  for (std::size_t size : {wall_particle_.size(), wall_xi_.size(), wall_theta_.size(),
                           wall_kt_.size(), wall_kr_.size()})
    if (size != nw)
      throw InputError(a.where() + "walls: not one entry per sphere-wall candidate");
  for (std::size_t e = 0; e < nw; ++e)
    if (wall_of_[e] < 0 || std::size_t(wall_of_[e]) >= walls_.size() || wall_particle_[e] < 0 ||
        std::size_t(wall_particle_[e]) >= n_particles)
      throw InputError(a.where() + "walls: candidate " + std::to_string(e) +
                       " names a wall or particle outside the model");
  link_pairs_to_bonds();
}
} // namespace dembridge::dem
