#include "dem/contacts/contact_forces.h"
#include "dem/bonds/bond_store.h"
#include "dem/contacts/contact_kernel.h"
#include "dem/contacts/joint_contact.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace dembridge::dem
{
ContactForces::ContactForces(const ContactConfig& material, const std::vector<WallConfig>& walls)
    : material_(material)
{
  material_.validate();
  if (!material_.enabled())
    throw InputError("Contacts/model: contacts are off (model = none)" +
                     std::string(walls.empty() ? "" : ", but walls need a contact law"));
  for (const auto& w : walls)
  {
    w.validate();
    walls_.emplace_back(w);
  }
  const double zeta = material_.damping_ratio();
  damping_ = zeta > 0;
  // linear: the same springs against a wall as between two particles
  const double kt = material_.tangential_stiffness > 0 ? material_.tangential_stiffness
                                                       : 2.0 / 7.0 * material_.normal_stiffness;
  linear_pair_ = linear_wall_ = {material_.normal_stiffness, kt, zeta};
  // Hertz-Mindlin: two equal spheres, or a sphere and a rigid wall (hertz_mindlin.h)
  const double E = material_.youngs_modulus, nu = material_.poisson_ratio;
  const double G = E / (2.0 * (1.0 + nu));
  hertz_pair_ = {E / (2.0 * (1.0 - nu * nu)), G / (2.0 * (2.0 - nu)), -zeta};
  hertz_wall_ = {E / (1.0 - nu * nu), G / (2.0 - nu), -zeta};
  rolling_ = {material_.rolling_friction, material_.rolling_stiffness};
  monitor_.enabled = material_.monitor;
  const std::size_t nw = walls_.size();
  wall_offset_built_.assign(nw, 0.0);
  wall_force_.assign(nw, Vec3::Zero());
  wall_force_prev_.assign(nw, Vec3::Zero());
  wall_damping_force_.assign(nw, Vec3::Zero());
  point_now_.assign(nw, Vec3::Zero());
}

void ContactForces::attach(const ParticleStore& p, const BondStore& bonds)
{
  bonds_ = &bonds;
  const std::size_t n = p.size();
  // bonds of each particle, built once (bonds are never added during a run; the solver has
  // already put them in their final order)
  bond_start_.assign(n + 1, 0);
  for (std::size_t k = 0; k < bonds.size(); ++k)
    ++bond_start_[std::size_t(bonds.a[k]) + 1], ++bond_start_[std::size_t(bonds.b[k]) + 1];
  for (std::size_t i = 0; i < n; ++i)
    bond_start_[i + 1] += bond_start_[i];
  bond_partner_.resize(std::size_t(bond_start_[n]));
  bond_index_.resize(bond_partner_.size());
  std::vector<std::int32_t> fill(bond_start_.begin(), bond_start_.end() - 1);
  for (std::size_t k = 0; k < bonds.size(); ++k)
  {
    const auto a = std::size_t(bonds.a[k]), b = std::size_t(bonds.b[k]);
    bond_partner_[std::size_t(fill[a])] = bonds.b[k], bond_index_[std::size_t(fill[a]++)] = int(k);
    bond_partner_[std::size_t(fill[b])] = bonds.a[k], bond_index_[std::size_t(fill[b]++)] = int(k);
  }
  joint_side_.clear();
  joint_grain_.clear();
  if (bonds.sliding_joints)
  {
    joint_side_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      joint_side_[i] = bonds.sliding_joints->side(p.reference_position[i]);
    if (bonds.sliding_joints->has_boundaries())
    {
      if (p.grain.size() != n)
        throw InputError("Bond class grain_boundary/joint friction: sliding grain boundaries "
                         "need every particle's grain, which a run over several ranks does "
                         "not keep");
      joint_grain_ = p.grain;
    }
  }
  if (!(list_.skin() > 0)) // else fixed over the whole model (fix_skin)
    fix_skin(p);
  if (damping_)
  {
    damping_force_.assign(n, Vec3::Zero());
    damping_torque_.assign(n, Vec3::Zero());
  }
}

void ContactForces::fix_skin(const ParticleStore& p)
{
  double skin = material_.skin;
  if (!(skin > 0)) // default: a fifth of the smallest radius
  {
    skin = std::numeric_limits<double>::infinity();
    for (double r : p.radius)
      skin = std::min(skin, 0.2 * r);
    if (!std::isfinite(skin))
      skin = 0;
  }
  list_.set_skin(skin);
}

void ContactForces::rebuild(const ParticleStore& p, double /*time*/)
{
  const auto& x = p.position;
  const auto& r = p.radius;
  list_.build(x, r, owned_);
  const std::size_t np = list_.size();
  const auto& prev = list_.previous_index();
  std::swap(xi_, xi_old_), std::swap(theta_, theta_old_);
  std::swap(kt_, kt_old_), std::swap(kr_, kr_old_);
  xi_.resize(np), theta_.resize(np), kt_.resize(np), kr_.resize(np);
  for (std::size_t k = 0; k < np; ++k)
  {
    const std::int32_t o = prev[k];
    xi_[k] = o >= 0 ? xi_old_[std::size_t(o)] : Vec3::Zero();
    theta_[k] = o >= 0 ? theta_old_[std::size_t(o)] : Vec3::Zero();
    kt_[k] = o >= 0 ? kt_old_[std::size_t(o)] : 0.0;
    kr_[k] = o >= 0 ? kr_old_[std::size_t(o)] : 0.0;
  }
  link_pairs_to_bonds();

  // Sphere-wall candidates: gap below the skin; sorted by (wall, particle) and merged with the
  // previous candidates to carry their springs over.
  std::swap(wall_of_, wall_of_old_), std::swap(wall_particle_, wall_particle_old_);
  std::swap(wall_xi_, wall_xi_old_), std::swap(wall_theta_, wall_theta_old_);
  std::swap(wall_kt_, wall_kt_old_), std::swap(wall_kr_, wall_kr_old_);
  wall_of_.clear(), wall_particle_.clear(), wall_xi_.clear(), wall_theta_.clear();
  wall_kt_.clear(), wall_kr_.clear();
  std::size_t o = 0;
  for (std::size_t w = 0; w < walls_.size(); ++w)
  {
    const Vec3& n = walls_[w].normal;
    wall_offset_built_[w] = point_now_[w].dot(n);
    for (std::size_t i = 0; i < std::min(p.size(), owned_); ++i) // a ghost: its owner's
    {
      if ((x[i] - point_now_[w]).dot(n) - r[i] >= list_.skin())
        continue;
      while (o < wall_of_old_.size() &&
             (std::size_t(wall_of_old_[o]) < w ||
              (std::size_t(wall_of_old_[o]) == w && std::size_t(wall_particle_old_[o]) < i)))
        ++o;
      const bool kept = o < wall_of_old_.size() && std::size_t(wall_of_old_[o]) == w &&
                        std::size_t(wall_particle_old_[o]) == i;
      wall_of_.push_back(std::int32_t(w));
      wall_particle_.push_back(std::int32_t(i));
      wall_xi_.push_back(kept ? wall_xi_old_[o] : Vec3::Zero());
      wall_theta_.push_back(kept ? wall_theta_old_[o] : Vec3::Zero());
      wall_kt_.push_back(kept ? wall_kt_old_[o] : 0.0);
      wall_kr_.push_back(kept ? wall_kr_old_[o] : 0.0);
    }
  }
  if (!history_key_.empty())
    take_distributed_history();
}

void ContactForces::add_forces(ParticleStore& p, double time, double dt, bool record)
{
  if (!bonds_)
    throw std::logic_error("ContactForces: add it to a solver (attach) before the first step");
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  for (std::size_t w = 0; w < walls_.size(); ++w)
    point_now_[w] = walls_[w].point(time);
  bool stale = list_.needs_rebuild(p.position);
  for (std::size_t w = 0; w < walls_.size() && !stale; ++w)
    stale =
        std::abs(point_now_[w].dot(walls_[w].normal) - wall_offset_built_[w]) > 0.5 * list_.skin();
  if (stale)
    rebuild(p, time);
  search_seconds_ += std::chrono::duration<double>(clock::now() - start).count();

  for (std::size_t w = 0; w < walls_.size(); ++w)
    wall_force_[w].setZero(), wall_damping_force_[w].setZero();
  const bool rolling = rolling_.friction > 0;
  auto with_law = [&]<class Law>()
  {
    if (rolling)
    {
      if (damping_)
        record ? compute<Law, true, true, true>(p, time, dt)
               : compute<Law, true, true, false>(p, time, dt);
      else
        record ? compute<Law, true, false, true>(p, time, dt)
               : compute<Law, true, false, false>(p, time, dt);
    }
    else
    {
      if (damping_)
        record ? compute<Law, false, true, true>(p, time, dt)
               : compute<Law, false, true, false>(p, time, dt);
      else
        record ? compute<Law, false, false, true>(p, time, dt)
               : compute<Law, false, false, false>(p, time, dt);
    }
  };
  const auto searched = clock::now();
  if (material_.model == ContactModel::linear)
    with_law.operator()<LinearSpringDashpot>();
  else
    with_law.operator()<HertzMindlin>();
  contact_seconds_ += std::chrono::duration<double>(clock::now() - searched).count();
  if (monitor_.enabled)
    update_monitor(p, time, dt);
  if (platens_.enabled)
    update_platens(time);
}

void ContactForces::update_platens(double time)
{
  auto& t = platens_;
  const auto lo = std::size_t(t.lower), up = std::size_t(t.upper);
  t.stress = -(wall_force_[lo].dot(walls_[lo].normal) + wall_force_[up].dot(walls_[up].normal)) /
             (2.0 * t.area);
  t.strain = (walls_[lo].displacement(time).dot(walls_[lo].normal) +
              walls_[up].displacement(time).dot(walls_[up].normal)) /
             t.length;
  if (t.stress > t.peak_stress)
    t.peak_stress = t.stress, t.strain_at_peak = t.strain, t.time_at_peak = time;
}

void ContactForces::measure_platens(int lower, int upper, double area)
{
  const int n = int(walls_.size());
  if (lower < 0 || upper < 0 || lower >= n || upper >= n || lower == upper)
    throw InputError("Contacts/platens: expected two different walls");
  const Wall &lo = walls_[std::size_t(lower)], &up = walls_[std::size_t(upper)];
  if (!(lo.normal.dot(up.normal) < -0.999))
    throw InputError("Contacts/platens: the walls '" + lo.name + "' and '" + up.name +
                     "' must face each other (opposite normals)");
  const double length = (up.point0 - lo.point0).dot(lo.normal);
  if (!(length > 0) || !(area > 0))
    throw InputError("Contacts/platens: the specimen must lie between the walls '" + lo.name +
                     "' and '" + up.name + "'");
  platens_ = {};
  platens_.enabled = true;
  platens_.lower = lower, platens_.upper = upper, platens_.area = area, platens_.length = length;
}

template <class Law, bool rolling, bool damping, bool record>
void ContactForces::compute(ParticleStore& p, double time, double dt)
{
  const Law* pair_law;
  const Law* wall_law;
  if constexpr (std::is_same_v<Law, LinearSpringDashpot>)
    pair_law = &linear_pair_, wall_law = &linear_wall_;
  else
    pair_law = &hertz_pair_, wall_law = &hertz_wall_;
  const Vec3* x = p.position.data();
  const Vec3* v = p.velocity.data();
  const Vec3* w = p.angular_velocity.data();
  const double* r = p.radius.data();
  const double* m = p.mass.data();
  Vec3* F = p.force.data();
  Vec3* T = p.torque.data();
  const BondState* state = bonds_->state.data();
  const std::int32_t* first = list_.first().data();
  const std::int32_t* second = list_.second().data();
  const double mu = material_.friction;
  double stored = 0, slip = 0, dissipation = 0, activation = 0;
  std::size_t active = 0;

  auto note = [&](bool wall, std::int32_t a, std::int32_t b, double delta, double force, double v_n)
  {
    monitor_.max_overlap = std::max(monitor_.max_overlap, delta);
    monitor_.max_force = std::max(monitor_.max_force, force);
    if (monitor_.started)
      return;
    monitor_.started = true;
    monitor_.wall = wall, monitor_.a = a, monitor_.b = b;
    monitor_.approach_speed = std::max(0.0, -v_n);
    monitor_.start_time = monitor_.approach_speed > 0
                              ? std::max(time - dt, time - delta / monitor_.approach_speed)
                              : time;
    monitor_.last_overlap = delta;
  };

  // a pair across a sliding joint's plane: the unbonded joint (joint_contact.h). kt_ < 0 marks
  // a pair apart that has had its chance of a bond's hand-over (eq. 8 there) or never had a
  // bond; theta_ (a joint turns no particle: no rolling spring) holds u_0 n, the approach the
  // joint's springs start from (eq. 8b)
  const SlidingJoints* joints = joint_side_.empty() ? nullptr : &*bonds_->sliding_joints;
  const Vec3* X = p.reference_position.data();
  double joint_friction = 0;
  auto joint_pair = [&](std::size_t k, std::size_t i, std::size_t j, std::int32_t bond, bool book)
  {
    // a weak plane's normal, or the grains' boundary's (sliding_joints.h)
    const bool plane = pair_joint_[k] == 1;
    const Vec3 n = !plane ? joints->boundary_normal(joint_grain_[i], joint_grain_[j])
                   : joint_side_[i] < joint_side_[j] ? joints->normal
                                                     : Vec3(-joints->normal);
    double reach = r[i] + r[j];
    if (bond >= 0)
      reach = std::max(reach, bonds_->rest_length[std::size_t(bond)]);
    const double mu_j = plane ? joints->friction : joints->boundary_friction;
    const double m_eff = m[i] * m[j] / (m[i] + m[j]);
    const double r_eff = bond >= 0 ? 0.0 : r[i] * r[j] / (r[i] + r[j]);
    // the joint's springs: a broken bond's, or the contact law's
    auto with_springs = [&](auto&& act)
    {
      if (bond >= 0)
        return act(
            LinearSpringDashpot{bonds_->kn[std::size_t(bond)], bonds_->ks[std::size_t(bond)], 0.0});
      return act(*pair_law);
    };
    const double u_0 = theta_[k].dot(n);
    double u_n = joint_approach(n, x[i], x[j], X[i], X[j]) - u_0; // eq. (2)
    if ((x[j] - x[i]).squaredNorm() >= reach * reach || !(u_n > 0))
    {
      if (kt_[k] > 0 && book) // the joint has just opened or left reach: what it held goes
      {
        const double u_before =
            joint_approach(n, x[i] - dt * v[i], x[j] - dt * v[j], X[i], X[j]) - u_0;
        joint_friction += with_springs(
            [&](const auto& law) {
              return joint_release(law, n, u_before, v[j] - v[i], r_eff, m_eff, dt, xi_[k], kt_[k]);
            });
      }
      if (kt_[k] >= 0)
        xi_[k].setZero(), kt_[k] = -1;
      return;
    }
    const bool hand_over = bond >= 0 && kt_[k] == 0.0, was_open = !(kt_[k] > 0);
    if (was_open)
      kt_[k] = 0;
    if (hand_over) // at the pair's first step after its bond broke: eq. (8), (8b)
    {
      const auto b = std::size_t(bond);
      const double kn = bonds_->kn[b], ks = bonds_->ks[b];
      const double released = bonds_->dissipated.empty() ? 0.0 : bonds_->dissipated[b];
      const double u_start = joint_start_approach(u_n, released, kn, ks, mu_j);
      theta_[k] = (u_n - u_start) * n;
      u_n = u_start;
      if (!(u_n > 0)) // nothing to hand over: apart from now on
      {
        kt_[k] = -1;
        return;
      }
      xi_[k] = joint_shear_handover(n, x[i], x[j], X[i], X[j], ks, mu_j, kn * u_n);
    }
    const JointContactOutput out = with_springs(
        [&](const auto& law) {
          return joint_contact_force(law, n, u_n, v[j] - v[i], r_eff, m_eff, mu_j, dt, xi_[k],
                                     kt_[k]);
        });
    F[j] += out.force;
    F[i] -= out.force;
    if (!book)
      return;
    if (was_open) // the energy it starts with, in the solver's time-centred form
    {
      const double start = out.energy - 0.5 * dt * out.power;
      if (hand_over) // taken from the fracture energy, as a broken bond's sphere contact below
        activation += start;
      else // a pair coming within reach of a compressed plane (joint_contact.h)
        joint_friction -= start;
    }
    ++active;
    joint_friction += out.slip;
    if constexpr (record)
      stored += out.energy;
    if (monitor_.enabled)
      note(false, std::int32_t(i), std::int32_t(j), u_n, out.normal_force, (v[j] - v[i]).dot(n));
  };

  const std::size_t np = list_.size();
  for (std::size_t k = 0; k < np; ++k)
  {
    const std::int32_t bond = pair_bond_[k];
    if (bond >= 0 && state[bond] != BondState::broken)
      continue; // an intact bond carries this pair
    auto i = std::size_t(first[k]), j = std::size_t(second[k]);
    if (global_id_ && (*global_id_)[i] > (*global_id_)[j]) // the same on every rank
      std::swap(i, j);
    const bool book = i < owned_; // on the rank that owns the lower id
    if (joints && pair_joint_[k])
    {
      joint_pair(k, i, j, bond, book);
      continue;
    }
    const Vec3 d = x[j] - x[i];
    const double dist2 = d.squaredNorm(), reach = r[i] + r[j];
    if (dist2 >= reach * reach || dist2 == 0.0)
    {
      if (kt_[k] > 0) // the contact has just opened: its springs go
        xi_[k].setZero(), theta_[k].setZero(), kt_[k] = kr_[k] = 0;
      continue;
    }
    const double dist = std::sqrt(dist2), delta = reach - dist;
    const Vec3 n = d / dist;
    const ContactInput in{n,
                          delta,
                          r[i] - 0.5 * delta,
                          r[j] - 0.5 * delta,
                          v[i],
                          w[i],
                          v[j],
                          w[j],
                          0.5 * (w[i] + w[j]).dot(n),
                          r[i] * r[j] / reach,
                          m[i] * m[j] / (m[i] + m[j])};
    const bool was_open = kt_[k] == 0.0;
    const ContactOutput out = contact_force<Law, rolling>(*pair_law, in, mu, rolling_, dt,
                                                          {xi_[k], theta_[k], kt_[k], kr_[k]});
    F[j] += out.force;
    F[i] -= out.force;
    T[i] += out.torque_i;
    T[j] += out.torque_j;
    if constexpr (damping)
    {
      // dashpot resultants per particle, for the dashpot's work with v^{n+1/2}
      const Vec3 arm_force = n.cross(out.damping_force);
      damping_force_[j] += out.damping_force;
      damping_torque_[j] -= in.arm_j * arm_force;
      damping_force_[i] -= out.damping_force;
      damping_torque_[i] -= in.arm_i * arm_force;
    }
    if (!book)
      continue;
    if (bond >= 0 && was_open) // a broken bond's pair, touching from the first step on: its
      activation += out.energy - 0.5 * dt * out.power; // in the solver's time-centred form
    ++active;
    slip += out.slip;
    if constexpr (damping)
      dissipation += out.damping;
    if constexpr (record)
      stored += out.energy;
    if (monitor_.enabled)
      note(false, std::int32_t(i), std::int32_t(j), delta, out.normal_force, (v[j] - v[i]).dot(n));
  }

  for (std::size_t e = 0; e < wall_particle_.size(); ++e)
  {
    const auto iw = std::size_t(wall_of_[e]), i = std::size_t(wall_particle_[e]);
    const Vec3& n = walls_[iw].normal;
    const double gap = (x[i] - point_now_[iw]).dot(n) - r[i];
    if (gap >= 0.0)
    {
      if (wall_kt_[e] > 0)
        wall_xi_[e].setZero(), wall_theta_[e].setZero(), wall_kt_[e] = wall_kr_[e] = 0;
      continue;
    }
    const double delta = -gap;
    const Vec3 v_wall = (point_now_[iw] - walls_[iw].point(time - dt)) / dt; // v^{n-1/2}
    const ContactInput in{n,   delta, 0.0, r[i] - 0.5 * delta, v_wall, Vec3::Zero(), v[i], w[i],
                          0.0, r[i],  m[i]};
    const ContactOutput out = contact_force<Law, rolling>(
        *wall_law, in, mu, rolling_, dt, {wall_xi_[e], wall_theta_[e], wall_kt_[e], wall_kr_[e]});
    ++active;
    F[i] += out.force;
    T[i] += out.torque_j;
    wall_force_[iw] -= out.force;
    slip += out.slip;
    if constexpr (damping)
    {
      dissipation += out.damping;
      damping_force_[i] += out.damping_force;
      damping_torque_[i] -= in.arm_j * n.cross(out.damping_force);
      wall_damping_force_[iw] += out.damping_force;
    }
    if constexpr (record)
      stored += out.energy;
    if (monitor_.enabled)
      note(true, std::int32_t(iw), std::int32_t(i), delta, out.normal_force,
           (v[i] - v_wall).dot(n));
  }

  slip_ += slip + joint_friction;
  joint_friction_ += joint_friction;
  activation_ += activation;
  damping_work_ += 0.5 * dt * dissipation; // the half with v^{n-1/2}
  if constexpr (record)
    stored_ = stored;
  n_active_ = active;
  contact_updates_ += long(active);
}

void ContactForces::update_monitor(const ParticleStore& p, double time, double dt)
{
  auto& mon = monitor_;
  if (!mon.started || mon.finished)
    return;
  const auto b = std::size_t(mon.b);
  double overlap, v_n;
  if (mon.wall)
  {
    const Wall& w = walls_[std::size_t(mon.a)];
    overlap = p.radius[b] - (p.position[b] - point_now_[std::size_t(mon.a)]).dot(w.normal);
    v_n =
        (p.velocity[b] - (point_now_[std::size_t(mon.a)] - w.point(time - dt)) / dt).dot(w.normal);
  }
  else
  {
    const auto a = std::size_t(mon.a);
    const Vec3 d = p.position[b] - p.position[a];
    overlap = p.radius[a] + p.radius[b] - d.norm();
    v_n = (p.velocity[b] - p.velocity[a]).dot(d.normalized());
  }
  if (overlap > 0)
  {
    mon.last_overlap = overlap;
    return;
  }
  mon.finished = true;
  mon.end_time = time - dt + dt * mon.last_overlap / (mon.last_overlap - overlap);
  mon.rebound_speed = v_n;
}

void ContactForces::after_update(const ParticleStore& p, double time, double dt, bool /*record*/)
{
  if (damping_)
  {
    // the dashpots' work with v^{n+1/2}: the second half of d^n . (v^{n-1/2} + v^{n+1/2}) dt/2
    double lead = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      if (i < owned_) // a ghost's is its owner's
        lead -=
            damping_force_[i].dot(p.velocity[i]) + damping_torque_[i].dot(p.angular_velocity[i]);
      damping_force_[i].setZero();
      damping_torque_[i].setZero();
    }
    for (std::size_t w = 0; w < walls_.size(); ++w)
      lead += wall_damping_force_[w].dot(walls_[w].point(time + dt) - point_now_[w]) / dt;
    damping_lead_ = 0.5 * dt * lead;
    damping_work_ += damping_lead_;
  }
  for (std::size_t w = 0; w < walls_.size(); ++w)
  {
    // trapezoidal work of the wall on the particles over [t_{n-1}, t_n]
    const Vec3 on_particles = -wall_force_[w];
    wall_work_ +=
        0.5 * (wall_force_prev_[w] + on_particles).dot(point_now_[w] - walls_[w].point(time - dt));
    wall_force_prev_[w] = on_particles;
  }
}

void ContactForces::add_energy(EnergyBalance& e) const
{
  e.contact_strain += stored_;
  e.friction += slip_;
  // at t_n the dashpot work counts d^n . v^{n-1/2} dt/2 but not yet the half with v^{n+1/2}
  e.contact_damping += damping_work_ - damping_lead_;
  e.wall_work += wall_work_;
  // A bond that breaks while its spheres overlap hands its pair to a contact that starts with
  // the stored energy U_c(delta) of that overlap: the solver has booked the bond's whole strain
  // energy as fracture (in the leapfrog's time-centred form U_b - dt/2 dU_b/dt, the bond's force
  // missing from step n on), but U_c of it (in the same form) was not released. It moves from
  // fracture (the solver's running sum, hence only the part not yet moved) to the contact's stored
  // energy.
  e.fracture -= activation_ - activation_booked_;
  activation_booked_ = activation_;
}
} // namespace dembridge::dem
