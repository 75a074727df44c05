#include "dem/solvers/explicit_solver.h"
#include "dem/bonds/bond_block.h"
#include "dem/solvers/bond_partition.h"
#include "dem/solvers/orientation_update.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace dembridge::dem
{
ExplicitSolver::ExplicitSolver(ParticleStore& particles, BondStore& bonds,
                               std::vector<Group> groups, std::vector<Constraint> constraints,
                               std::vector<Load> loads, const SolverSettings& settings)
    : p_(particles), b_(bonds), groups_(std::move(groups)), constraints_(std::move(constraints)),
      loads_(std::move(loads)), settings_(settings)
{
  if (!(settings_.time_step > 0))
    throw InputError("Simulation/time step: must be positive");
  if (settings_.particle_damping < 0 || settings_.particle_damping >= 1)
    throw InputError("Damping/particle damping: must lie in [0, 1)");
  if (settings_.mass_damping < 0 || settings_.mass_damping * settings_.time_step >= 1)
    throw InputError("Damping/mass damping: must be >= 0 and below 1 / time step (" +
                     std::to_string(1 / settings_.time_step) + " 1/s)");
  settings_.threads = std::max(1, settings_.threads);
  owned_ = std::min(settings_.owned_particles, p_.size());
  std::vector<char> touched(p_.size(), 0);
  for (const auto& c : constraints_)
    for (int i : groups_.at(c.group).members)
      touched[i] = 1;
  for (const auto& l : loads_)
    if (l.prescribes_motion())
      for (int i : groups_.at(l.group).members)
        touched[i] = 1;
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (touched[i])
      constrained_.push_back(int(i));
  constrained_v_.resize(constrained_.size());
  prescribed_v_.assign(constrained_.size(), Vec3::Zero());
  prescribed_w_.assign(constrained_.size(), Vec3::Zero());
  constrained_w_.resize(constrained_.size());
  constrained_reaction_.assign(constrained_.size(), Vector6::Zero());
  applied_pressure_.assign(loads_.size(), 0.0);
  group_reaction_.assign(loads_.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t g = 0; g < groups_.size() && g < 32; ++g)
    for (int i : groups_[g].members)
      p_.group_mask[i] |= 1u << g;
  if (b_.has_failure() &&
      (b_.tensile_strength.size() != b_.size() || b_.failure_mode.size() != b_.size()))
    throw std::logic_error("ExplicitSolver: a failure law without per-bond strengths "
                           "(assign_bond_strengths)");
  partition_bonds();
  // Failure buffers: bond failures are rare; a reserve per range keeps the loop free of
  // allocation but for the odd burst (amortised).
  for (int phase = 0; phase < 4; ++phase)
  {
    phase_buffer_[phase] = crack_buffers_.size();
    crack_buffers_.resize(crack_buffers_.size() + phases_[phase].size());
  }
  if (b_.has_failure())
  {
    for (auto& buffer : crack_buffers_)
      buffer.reserve(64);
    cracks_.reserve(256);
  }
  for (std::size_t k = 0; k < b_.size(); ++k)
    dashpots_ = dashpots_ || b_.damping_force[k] > 0 || b_.damping_moment[k] > 0;
  const std::size_t record_size =
      dashpots_ ? particle_record_size<true> : particle_record_size<false>;
  particle_sums_.assign(record_size * p_.size(), 0.0);
  // energy_.initial is set by the first step, from the leapfrog state at t_0 (integrate())
}

// Bonds grouped by the particle index chunks they join (bond_partition.h); the particles are in
// spatial order (renumbering.h), so each chunk is a compact region.
void ExplicitSolver::partition_bonds()
{
  BondPartition part = partition_bonds_by_index(b_.a, b_.b, p_.size(), settings_.threads);
  b_.reorder(part.order); // every per-bond array, strengths and damage included
  phases_ = std::move(part.phases);
}

std::size_t ExplicitSolver::memory_bytes() const
{
  auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  std::size_t n = bytes(particle_sums_) + bytes(constrained_) + bytes(prescribed_v_) +
                  bytes(prescribed_w_) + bytes(constrained_v_) + bytes(constrained_w_) +
                  bytes(constrained_reaction_) + bytes(cracks_);
  for (const auto& buffer : crack_buffers_)
    n += bytes(buffer);
  return n;
}

void ExplicitSolver::apply_loads()
{
  const double t = time_, dt = settings_.time_step;
  // Supports and prescribed motion, evaluated at the half step the velocity update targets.
  for (std::size_t c = 0; c < constrained_.size(); ++c)
  {
    const int i = constrained_[c];
    p_.dof_mask[i] = 0;
    prescribed_v_[c].setZero();
    prescribed_w_[c].setZero();
    constrained_v_[c] = p_.velocity[i];
    constrained_w_[c] = p_.angular_velocity[i];
  }
  for (const auto& c : constraints_)
    for (int i : groups_[c.group].members)
      p_.dof_mask[i] |= c.dofs;
  for (std::size_t k = 0; k < loads_.size(); ++k)
  {
    const Load& l = loads_[k];
    const auto& members = groups_[l.group].members;
    if (l.kind == LoadKind::pressure)
    {
      // F = (p_0 factor(t) + R sigma_ref) A d (loads.h), sigma_ref from the last step's reactions
      const double p =
          l.active(t) ? l.pressure * l.factor(t) +
                            (l.ratio_load >= 0 ? l.ratio * reference_stress(l.ratio_load) : 0.0)
                      : 0.0;
      const double per_particle = l.area / double(members.size());
      const Vec3 share = l.value * (p * per_particle);
      // trapezoidal work with the previous step's pressure
      const Vec3 mean_share =
          steps_ > 0 ? Vec3(l.value * (0.5 * (p + applied_pressure_[k]) * per_particle))
                     : Vec3::Zero();
      applied_pressure_[k] = p;
      for (int i : members)
      {
        p_.force[i] += share;
        energy_.external += dt * mean_share.dot(p_.velocity[i]);
      }
    }
    else if (l.prescribes_motion())
    {
      if (!l.active(t + 0.5 * dt))
        continue;
      // a displacement load moves its DOFs exactly by u(t + dt) - u(t) over the step
      const Vec3 value =
          l.kind == LoadKind::displacement
              ? Vec3(l.value *
                     ((l.displacement_fraction(t + dt) - l.displacement_fraction(t)) / dt))
              : Vec3(l.value * l.factor(t + 0.5 * dt));
      const bool rot = l.kind == LoadKind::angular_velocity;
      for (int i : members)
      {
        const std::size_t c = slot(i);
        for (int k = 0; k < 3; ++k)
          if (l.components & (1u << k))
          {
            p_.dof_mask[i] |= std::uint8_t(1u << (k + (rot ? 3 : 0)));
            (rot ? prescribed_w_[c] : prescribed_v_[c])[k] = value[k];
          }
      }
    }
    else
    {
      const double inv_n = 1.0 / double(members.size());
      const Vec3 share = l.value * (l.factor(t) * inv_n);
      // trapezoidal work 1/2 (F^{n-1} + F^n) . (x^n - x^{n-1}) (thesis eq. 52)
      const Vec3 mean_share =
          steps_ > 0 ? Vec3(0.5 * (share + l.value * (l.factor(t - dt) * inv_n))) : Vec3::Zero();
      const bool moment = l.kind == LoadKind::moment;
      for (int i : members)
      {
        (moment ? p_.torque[i] : p_.force[i]) += share;
        energy_.external += dt * mean_share.dot(moment ? p_.angular_velocity[i] : p_.velocity[i]);
      }
    }
  }
}

double ExplicitSolver::reference_stress(int load) const
{
  const double shared = group_reaction_[std::size_t(load)];
  return (std::isnan(shared) ? own_group_reaction(load) : shared) / loads_[std::size_t(load)].area;
}

void ExplicitSolver::set_group_reaction(int load, double reaction)
{
  group_reaction_.at(std::size_t(load)) = reaction;
}

double ExplicitSolver::own_group_reaction(int load) const
{
  const Load& l = loads_[std::size_t(load)];
  const Vec3 direction = l.value.normalized();
  double reaction = 0;
  for (int i : groups_[l.group].members)
  {
    const std::size_t c = slot(i);
    reaction += constrained_reaction_[c].head<3>().dot(direction);
  }
  return reaction;
}

template <bool record> void ExplicitSolver::integrate()
{
  const double dt = settings_.time_step, gamma = settings_.particle_damping;
  const double mass_damping = settings_.mass_damping;
  const std::size_t n = owned_; // ghosts (distributed runs) are their owners' to integrate
  double dissipation = 0, kinetic = 0, vmax2 = 0, lead = 0, unbalanced = 0;
  long n_free = 0;
  const std::size_t n_blocked = n - n % 8; // particles whose orientation turns in blocks of 8
  auto& x = p_.position;
  auto& v = p_.velocity;
  auto& w = p_.angular_velocity;
  auto& q = p_.orientation;
  auto& F = p_.force;
  auto& M = p_.torque;
#pragma omp parallel for num_threads(settings_.threads) schedule(static) reduction(+ : dissipation, kinetic, lead, unbalanced, n_free) reduction(max : vmax2)
  for (std::size_t i = 0; i < n; ++i)
  {
    const double m = p_.mass[i], I = p_.inertia[i];
    const std::uint8_t mask = p_.dof_mask[i];
    const Vec3 v0 = v[i], w0 = w[i];
    if constexpr (record)
      if ((mask & 7u) != 7u) // the net force on the free translations (before it turns into
      {                      // reactions on the constrained ones)
        Vec3 free = F[i];
        for (int k = 0; k < 3; ++k)
          if (mask & (1u << k))
            free[k] = 0;
        unbalanced += free.norm();
        ++n_free;
      }
    Vec3 mass_damping_force = Vec3::Zero();
    if (mass_damping > 0) // -c m v^{n-1/2}; on a constrained DOF it enters the reaction
    {
      mass_damping_force = -mass_damping * m * v0;
      F[i] += mass_damping_force;
    }
    Vec3 v1, w1;
    if (mask == 0 && gamma == 0)
    {
      // the common case, kept branch-free: eq. 40 and eq. 44
      v1 = v0 + (dt / m) * F[i];
      w1 = w0 + (dt / I) * M[i];
    }
    else
    {
      // One DOF, translation (eq. 40) or rotation (eq. 44): a constrained DOF takes its
      // prescribed velocity and `load` becomes the support reaction; a free one feels particle
      // damping (paper eq. 11-12).
      auto update =
          [&](bool constrained, double prescribed, double before, double& load, double inertia)
      {
        if (constrained)
        {
          load = inertia * (prescribed - before) / dt - load;
          return prescribed;
        }
        const double damp = gamma * std::abs(load) * (before > 0 ? 1.0 : (before < 0 ? -1.0 : 0.0));
        const double after = before + dt * (load - damp) / inertia;
        dissipation += damp * 0.5 * (before + after) * dt;
        if constexpr (record)
          lead += damp * 0.5 * after * dt;
        return after;
      };
      // the prescribed values of a constrained particle; a mask left by someone else (a static
      // solve) holds its DOFs at rest, as before the values moved into the solver
      const std::size_t c = mask ? slot(int(i)) : constrained_.size();
      const bool own = c < constrained_.size() && constrained_[c] == int(i);
      const Vec3 pv = own ? prescribed_v_[c] : Vec3::Zero();
      const Vec3 pw = own ? prescribed_w_[c] : Vec3::Zero();
      for (int k = 0; k < 3; ++k)
      {
        v1[k] = update(mask & (1u << k), pv[k], v0[k], F[i][k], m);
        w1[k] = update(mask & (1u << (k + 3)), pw[k], w0[k], M[i][k], I);
      }
    }
    if (mass_damping > 0)
    {
      dissipation -= 0.5 * dt * mass_damping_force.dot(v0 + v1);
      if constexpr (record)
        lead -= 0.5 * dt * mass_damping_force.dot(v1);
    }
    if (dashpots_)
    {
      // work of the bond dashpots on this particle, d^n . (v^{n-1/2} + v^{n+1/2})/2 dt
      double* const sum = &particle_sums_[particle_record_size<true> * i];
      const Vec3 fd(sum + record_dashpot_force), md(sum + record_dashpot_moment);
      dissipation -= 0.5 * dt * (fd.dot(v0 + v1) + md.dot(w0 + w1));
      if constexpr (record)
        lead -= 0.5 * dt * (fd.dot(v1) + md.dot(w1));
      std::fill(sum + record_dashpot_force, sum + particle_record_size<true>, 0.0);
    }
    v[i] = v1;
    w[i] = w1;
    x[i] += dt * v1; // eq. 41
    // q <- exp(dt w / 2) q (eq. 45, orientation_update.h): the particles past the last full
    // block of eight here, the blocks after this loop
    if (std::size_t(i) >= n_blocked)
      update_orientation(q[i].coeffs().data(), w1.data(), dt);
    if constexpr (record)
    {
      // eq. 49, time-centred at t_n as 1/2 m v^{n-1/2}.v^{n+1/2}: the form the leapfrog
      // scheme conserves exactly for a linear undamped system
      kinetic += 0.5 * m * v0.dot(v1) + 0.5 * I * w0.dot(w1);
      vmax2 = std::max(vmax2, v1.squaredNorm());
    }
  }
  {
    // why: the raw doubles without dereferencing data(), which is null for no particles
    static_assert(sizeof(Quat) == 4 * sizeof(double) && sizeof(Vec3) == 3 * sizeof(double));
    double* const qd = reinterpret_cast<double*>(q.data());
    const double* const wd = reinterpret_cast<const double*>(w.data());
    const long blocks = long(n_blocked / 8);
#pragma omp parallel for num_threads(settings_.threads) schedule(static)
    for (long b = 0; b < blocks; ++b)
      update_orientations8(qd + 32 * b, wd + 24 * b, dt);
  }
  // Damping work (particle damping and dashpots): the running sum of d^n . (v^{n-1/2} +
  // v^{n+1/2})/2 dt runs half a
  // step ahead of t_n; the trapezoidal value at t_n drops the last half term ("lead").
  damping_work_ += dissipation;
  if (steps_ == 0)
  {
    // The balance starts at t_0 with the energy the leapfrog state holds there (shadow kinetic
    // energy + strain); damping work before t_0 (the first half step) is not counted.
    energy_.initial = kinetic + energy_.strain;
    damping_work_ = lead;
  }
  if constexpr (record)
  {
    energy_.damping = damping_work_ - lead;
    energy_.kinetic = kinetic;
    max_speed_ = std::sqrt(vmax2);
    unbalanced_mean_ = n_free > 0 ? unbalanced / double(n_free) : 0.0;
    unbalanced_sum_ = unbalanced, n_free_ = n_free;
  }
  // Work of supports with prescribed motion: 1/2 (R^{n-1} + R^n) . (x^n - x^{n-1}).
  for (std::size_t c = 0; c < constrained_.size(); ++c)
  {
    const int i = constrained_[c];
    const std::uint8_t mask = p_.dof_mask[i];
    for (int k = 0; k < 3; ++k)
    {
      const double R = mask & (1u << k) ? F[i][k] : 0.0;
      const double Rm = mask & (1u << (k + 3)) ? M[i][k] : 0.0;
      energy_.external += 0.5 * (constrained_reaction_[c][k] + R) * constrained_v_[c][k] * dt;
      energy_.external += 0.5 * (constrained_reaction_[c][k + 3] + Rm) * constrained_w_[c][k] * dt;
      constrained_reaction_[c][k] = R;
      constrained_reaction_[c][k + 3] = Rm;
    }
  }
}

void ExplicitSolver::step(bool record)
{
  record = record || steps_ == 0; // the first step fixes the initial energy
  // The bond loop sets the forces (the previous step's values, support reactions, are read
  // between steps); its per-particle sums are zero here, the dashpot parts zeroed in
  // integrate() right after their last use.
  if (sums_hold_evaluation_)
    std::fill(particle_sums_.begin(), particle_sums_.end(), 0.0), sums_hold_evaluation_ = false;
  record ? dispatch_bond_forces<true>() : dispatch_bond_forces<false>();
  apply_loads();
  for (auto* c : contributions_)
    c->add_forces(p_, time_, settings_.time_step, record);
  if (record)
    integrate<true>();
  else
    integrate<false>();
  for (auto* c : contributions_)
    c->after_update(p_, time_, settings_.time_step, record);
  if (record)
  {
    unbalanced_ratio_ = intact_force_ > 0 ? unbalanced_mean_ * double(n_intact_) / intact_force_
                                          : std::numeric_limits<double>::infinity();
    energy_.contact_strain = energy_.friction = energy_.contact_damping = energy_.wall_work = 0;
    for (auto* c : contributions_)
      c->add_energy(energy_);
    if (steps_ == 0) // stored energy at t_0 includes what the contributions hold
      energy_.initial += energy_.contact_strain;
  }
  time_ += settings_.time_step;
  ++steps_;
}

std::size_t ExplicitSolver::slot(int particle) const
{
  return std::size_t(std::lower_bound(constrained_.begin(), constrained_.end(), particle) -
                     constrained_.begin());
}

Vec3 ExplicitSolver::group_force(int group) const
{
  return total_force(p_, groups_.at(group));
}

Vec3 ExplicitSolver::group_mean_displacement(int group) const
{
  return mean_displacement(p_, groups_.at(group));
}

ExplicitSolver::RunningState ExplicitSolver::take_running_state()
{
  RunningState s;
  s.time = time_, s.steps = steps_, s.energy = energy_, s.damping_work = damping_work_;
  s.max_speed = max_speed_, s.unbalanced_mean = unbalanced_mean_;
  s.unbalanced_ratio = unbalanced_ratio_, s.unbalanced = unbalanced_parts();
  s.cracks = std::move(cracks_), s.broken_by_mode = broken_by_mode_;
  s.applied_pressure = applied_pressure_;
  cracks_.clear();
  return s;
}

void ExplicitSolver::set_running_state(RunningState&& s)
{
  time_ = s.time, steps_ = s.steps, energy_ = s.energy, damping_work_ = s.damping_work;
  max_speed_ = s.max_speed, unbalanced_mean_ = s.unbalanced_mean;
  unbalanced_ratio_ = s.unbalanced_ratio;
  unbalanced_sum_ = s.unbalanced.free_force, n_free_ = s.unbalanced.n_free;
  intact_force_ = s.unbalanced.intact_force, n_intact_ = s.unbalanced.n_intact;
  const std::size_t capacity = cracks_.capacity(); // the failure law's reserve
  cracks_ = std::move(s.cracks);
  cracks_.reserve(capacity);
  broken_by_mode_ = s.broken_by_mode;
  if (s.applied_pressure.size() == applied_pressure_.size()) // (empty: a state of figures only)
    applied_pressure_ = std::move(s.applied_pressure);
}

std::array<double, 6> ExplicitSolver::support_reaction(std::size_t i) const
{
  std::array<double, 6> r{};
  const std::size_t c = slot(int(i));
  if (c < constrained_.size() && constrained_[c] == int(i))
    for (int k = 0; k < 6; ++k)
      r[std::size_t(k)] = constrained_reaction_[c][k];
  return r;
}

void ExplicitSolver::set_support_reaction(std::size_t i, const std::array<double, 6>& reaction)
{
  const std::size_t c = slot(int(i));
  if (c < constrained_.size() && constrained_[c] == int(i))
    for (int k = 0; k < 6; ++k)
      constrained_reaction_[c][k] = reaction[std::size_t(k)];
}

double ExplicitSolver::last_ramp_end() const
{
  double t = 0;
  for (const auto& l : loads_)
    t = std::max(t, l.ramp_time);
  return t;
}
} // namespace dembridge::dem
