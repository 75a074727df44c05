#pragma once
// Forces that act on the particles beside the bonds and the loads: post-failure contacts and
// walls (dem/contacts/), the tie to a continuum in a coupled run (coupling/). The explicit solver
// calls each contribution once per step (one virtual call per step, none per particle or
// contact), in the order they were added:
//   1. bond forces at t_n (x^n, q^n; dashpots from v^{n-1/2});
//   2. the loads at t_n;
//   3. add_forces(): each contribution adds to p.force / p.torque;
//   4. the velocity and position update (v^{n+1/2}, x^{n+1}, q^{n+1});
//   5. after_update(): e.g. the work of dashpots and friction with v^{n+1/2}.
// On record steps the solver asks each contribution for its energy terms (add_energy adds
// them to the balance, dem/core/energy.h).
#include "dem/core/energy.h"
#include "dem/core/particle_store.h"
#include "dem/core/state_archive.h"
#include <limits>
#include <stdexcept>

namespace dembridge::dem
{
struct BondStore;

class StepContribution
{
public:
  virtual ~StepContribution() = default;
  /// Called once when the solver takes the contribution, after the solver has put the bonds in
  /// their final order: a contribution that reads particles or bonds (contacts skip bonded
  /// pairs) binds to them here.
  virtual void attach(const ParticleStore& /*p*/, const BondStore& /*bonds*/) {}
  /// Adds forces and torques at time t_n (positions x^n, velocities v^{n-1/2}).
  virtual void add_forces(ParticleStore& p, double time, double dt, bool record) = 0;
  /// After the update: velocities v^{n+1/2}, positions x^{n+1}; time is still t_n.
  virtual void after_update(const ParticleStore& /*p*/, double /*time*/, double /*dt*/,
                            bool /*record*/)
  {
  }
  /// Adds this contribution's terms (contact_strain, friction, contact_damping, wall_work, ...)
  /// to a balance whose contribution-owned fields the solver has zeroed.
  virtual void add_energy(EnergyBalance& /*e*/) const {}
  /// Largest stable time step this contribution allows (s); infinity: no limit.
  virtual double critical_time_step(const ParticleStore& /*p*/) const
  {
    return std::numeric_limits<double>::infinity();
  }
  /// Checkpoints: whether visit_state saves and restores all of this contribution's state.
  virtual bool checkpointable() const { return false; }
  /// Saves or restores the contribution's state between steps (dem/core/state_archive.h).
  virtual void visit_state(StateArchive& /*a*/)
  {
    throw std::logic_error("this step contribution cannot be checkpointed");
  }
};
} // namespace dembridge::dem
