// ExplicitSolver's checkpoint state (explicit_solver.h: visit_state). Between steps the
// leapfrog state is x^n, q^n, v^{n-1/2}, w^{n-1/2}; what else a step reads from the previous
// ones is named here: the running energy sums (damping work half a step ahead), the support
// reactions of the last step (the trapezoidal work of prescribed motion), the crack log and
// the per-mode counts, the pressures of the last step, and the last record's figures (max
// speed, unbalanced-force ratio).
// Scratch that every step overwrites before reading or leaves zero (the bond loop's
// per-particle sums, supports' velocities, failure buffers) is not stored.
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/run_state.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dembridge::dem
{
bool ExplicitSolver::checkpointable() const
{
  for (const auto* c : contributions_)
    if (!c->checkpointable())
      return false;
  return true;
}

void ExplicitSolver::continue_run(const double time, std::vector<CrackEvent> earlier_cracks)
{
  if (steps_ != 0)
    throw std::logic_error("ExplicitSolver::continue_run: after the first step");
  time_ = time;
  cracks_ = std::move(earlier_cracks);
  broken_by_mode_ = {};
  for (const auto& c : cracks_)
    ++broken_by_mode_[int(c.mode)];
  if (b_.has_failure() && cracks_.capacity() < cracks_.size() + 256)
    cracks_.reserve(cracks_.size() + 256);
}

void ExplicitSolver::visit_state(StateArchive& a)
{
  visit_particles(a, p_);
  const std::vector<std::size_t> bond_map = visit_bonds(a, b_);
  StateGroup group(a, "solver");
  double dt = settings_.time_step;
  a.io("time_step", dt);
  // why: the same case gives the same step to the last bit; another step is another run
  if (a.loading() && dt != settings_.time_step)
    throw InputError(a.where() + "time_step: " + std::to_string(dt) + " s in the checkpoint, " +
                     std::to_string(settings_.time_step) + " s in this run");
  a.io("time", time_);
  a.io("steps", steps_);
  {
    StateGroup energy(a, "energy");
    EnergyBalance& e = energy_;
    a.io("kinetic", e.kinetic);
    a.io("strain", e.strain);
    a.io("damping", e.damping);
    a.io("external", e.external);
    a.io("initial", e.initial);
    a.io("fracture", e.fracture);
    a.io("contact_strain", e.contact_strain);
    a.io("friction", e.friction);
    a.io("contact_damping", e.contact_damping);
    a.io("wall_work", e.wall_work);
  }
  a.io("damping_work", damping_work_);
  a.io("max_speed", max_speed_);
  a.io("unbalanced_mean", unbalanced_mean_);
  a.io("unbalanced_ratio", unbalanced_ratio_);
  // support reactions of the last step, six per constrained particle
  std::vector<std::int32_t> constrained = constrained_;
  std::vector<double> reaction;
  reaction.reserve(6 * constrained_reaction_.size());
  for (const auto& r : constrained_reaction_)
    reaction.insert(reaction.end(), r.data(), r.data() + 6);
  a.io("constrained_particles", constrained);
  a.io("constrained_reaction", reaction);
  if (a.loading())
  {
    if (constrained != constrained_ || reaction.size() != 6 * constrained_.size())
      throw InputError(a.where() + "constrained_particles: the checkpoint's supports and "
                                   "prescribed particles are not this model's");
    for (std::size_t c = 0; c < constrained_reaction_.size(); ++c)
      for (int k = 0; k < 6; ++k)
        constrained_reaction_[c][k] = reaction[6 * c + std::size_t(k)];
  }
  // pressures applied at the last step (their trapezoidal work); only cases that have one
  if (std::any_of(loads_.begin(), loads_.end(),
                  [](const Load& l) { return l.kind == LoadKind::pressure; }))
  {
    std::vector<double> pressure = applied_pressure_;
    a.io("applied_pressure", pressure);
    if (a.loading())
    {
      if (pressure.size() != applied_pressure_.size())
        throw InputError(a.where() + "applied_pressure: expected " +
                         std::to_string(applied_pressure_.size()) + " values");
      applied_pressure_ = pressure;
    }
  }
  std::vector<std::int64_t> by_mode(broken_by_mode_.begin(), broken_by_mode_.end());
  a.io("broken_by_mode", by_mode);
  if (a.loading())
  {
    if (by_mode.size() != broken_by_mode_.size())
      throw InputError(a.where() + "broken_by_mode: expected " +
                       std::to_string(broken_by_mode_.size()) + " counts");
    for (std::size_t m = 0; m < by_mode.size(); ++m)
      broken_by_mode_[m] = long(by_mode[m]);
  }
  visit_cracks(a, cracks_, a.loading() ? bond_map : std::vector<std::size_t>{});
  if (a.loading() && b_.has_failure() && cracks_.capacity() < 256)
    cracks_.reserve(256);
  int n_contributions = int(contributions_.size());
  a.io("contributions", n_contributions);
  if (a.loading() && n_contributions != int(contributions_.size()))
    throw InputError(a.where() + "contributions: " + std::to_string(n_contributions) +
                     " in the checkpoint (contacts, walls, coupling), " +
                     std::to_string(contributions_.size()) + " in this run");
  for (std::size_t c = 0; c < contributions_.size(); ++c)
  {
    StateGroup one(a, "contribution_" + std::to_string(c));
    contributions_[c]->visit_state(a);
  }
}
} // namespace dembridge::dem
