#include "dem/core/particle_store.h"
#include <numbers>

namespace dembridge::dem
{
void ParticleStore::add(const Vec3& x, double r, double rho)
{
  position.push_back(x);
  reference_position.push_back(x);
  velocity.push_back(Vec3::Zero());
  angular_velocity.push_back(Vec3::Zero());
  orientation.push_back(Quat::Identity());
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
  radius.push_back(r);
  mass.push_back(0.0);
  inertia.push_back(0.0);
  dof_mask.push_back(0);
  group_mask.push_back(0);
  coordination.push_back(0);
  id.push_back(std::int32_t(position.size() - 1));
  set_mass(size() - 1, rho * 4.0 / 3.0 * std::numbers::pi * r * r * r);
}

void ParticleStore::set_mass(std::size_t i, double m)
{
  mass[i] = m;
  inertia[i] = 0.4 * m * radius[i] * radius[i]; // thesis eq. 42
}

std::size_t ParticleStore::memory_bytes() const
{
  auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return bytes(position) + bytes(reference_position) + bytes(velocity) + bytes(angular_velocity) +
         bytes(orientation) + bytes(force) + bytes(torque) + bytes(radius) + bytes(mass) +
         bytes(inertia) + bytes(dof_mask) + bytes(group_mask) + bytes(coordination) + bytes(id) +
         bytes(grain);
}
} // namespace dembridge::dem
