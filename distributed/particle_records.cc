// A particle's state as it travels between ranks (particle_records.h).
#include "distributed/particle_records.h"
#include <algorithm>

namespace dembridge::distributed
{
using dem::Vec3;

void pack_state(const dem::ParticleStore& p, std::size_t i, std::int64_t id,
                std::uint32_t group_mask, const Reaction& reaction, double* out)
{
  auto put = [&](unsigned at, const double* v, unsigned n) { std::copy(v, v + n, out + at); };
  out[state::id] = double(id);
  put(state::reference_position, p.reference_position[i].data(), 3);
  put(state::velocity, p.velocity[i].data(), 3);
  put(state::angular_velocity, p.angular_velocity[i].data(), 3);
  put(state::orientation, p.orientation[i].coeffs().data(), 4);
  put(state::force, p.force[i].data(), 3);
  put(state::torque, p.torque[i].data(), 3);
  put(state::reaction, reaction.data(), 6);
  out[state::radius] = p.radius[i];
  out[state::mass] = p.mass[i];
  out[state::inertia] = p.inertia[i];
  out[state::dof_mask] = p.dof_mask[i];
  out[state::group_mask] = group_mask;
  out[state::coordination] = p.coordination[i];
  out[state::user_id] = p.id[i];
}

Reaction unpack_state(const double* in, dem::ParticleStore& p, std::size_t i)
{
  auto vec3 = [&](unsigned at) { return Vec3(in[at], in[at + 1], in[at + 2]); };
  p.reference_position[i] = vec3(state::reference_position);
  p.velocity[i] = vec3(state::velocity);
  p.angular_velocity[i] = vec3(state::angular_velocity);
  std::copy(in + state::orientation, in + state::orientation + 4, p.orientation[i].coeffs().data());
  p.force[i] = vec3(state::force);
  p.torque[i] = vec3(state::torque);
  p.radius[i] = in[state::radius];
  p.mass[i] = in[state::mass];
  p.inertia[i] = in[state::inertia];
  p.dof_mask[i] = std::uint8_t(in[state::dof_mask]);
  p.group_mask[i] = std::uint32_t(in[state::group_mask]);
  p.coordination[i] = int(in[state::coordination]);
  p.id[i] = std::int32_t(in[state::user_id]);
  Reaction r;
  std::copy(in + state::reaction, in + state::reaction + 6, r.begin());
  return r;
}

void resize(dem::ParticleStore& p, std::size_t n)
{
  p.position.resize(n), p.reference_position.resize(n), p.velocity.resize(n);
  p.angular_velocity.resize(n), p.orientation.resize(n), p.force.resize(n), p.torque.resize(n);
  p.radius.resize(n), p.mass.resize(n), p.inertia.resize(n), p.dof_mask.resize(n);
  p.group_mask.resize(n), p.coordination.resize(n), p.id.resize(n);
}
} // namespace dembridge::distributed
