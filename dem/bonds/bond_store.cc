#include "dem/bonds/bond_store.h"
#include <type_traits>

namespace dembridge::dem
{
void BondStore::add(std::int32_t ia, std::int32_t ib, double length, const Vec3& axis, BondModel m,
                    const BondStiffness& k)
{
  a.push_back(ia);
  b.push_back(ib);
  rest_length.push_back(length);
  rest_axis.push_back(axis);
  kn.push_back(k.kn);
  ks.push_back(k.ks);
  ktor.push_back(k.ktor);
  kben.push_back(k.kben);
  contact_fraction.push_back(k.contact_fraction);
  radius.push_back(k.radius);
  damping_force.push_back(0.0);
  damping_moment.push_back(0.0);
  model.push_back(m);
  state.push_back(BondState::intact);
  if (!force_records_dropped && force.size() + 1 == a.size()) // records kept (drop_force_records)
  {
    force.push_back(Vec3::Zero());
    moment.push_back(Vec3::Zero());
  }
}

void BondStore::reorder(const std::vector<std::size_t>& order)
{
  auto permute = [&](auto& v)
  {
    if (v.empty()) // failure arrays without a failure law
      return;
    std::remove_reference_t<decltype(v)> moved(order.size()); // exact size: no slack kept
    for (std::size_t k = 0; k < order.size(); ++k)
      moved[k] = v[order[k]];
    v.swap(moved);
  };
  permute(a), permute(b), permute(rest_length), permute(rest_axis);
  permute(kn), permute(ks), permute(ktor), permute(kben);
  permute(contact_fraction), permute(radius), permute(damping_force), permute(damping_moment);
  permute(model), permute(state), permute(bond_class), permute(basal_normal);
  permute(force), permute(moment);
  permute(tensile_strength), permute(shear_strength), permute(damage), permute(kappa_max);
  permute(kappa_ultimate), permute(dissipated), permute(failure_mode);
}

void BondStore::reserve(std::size_t n)
{
  for (auto* v : {&a, &b})
    v->reserve(n);
  for (auto* v : {&rest_length, &kn, &ks, &ktor, &kben, &contact_fraction, &radius, &damping_force,
                  &damping_moment})
    v->reserve(n);
  rest_axis.reserve(n);
  if (records_forces())
    force.reserve(n), moment.reserve(n);
  model.reserve(n), state.reserve(n);
}

BondStiffness BondStore::stiffness(std::size_t k) const
{
  BondStiffness s;
  s.kn = kn[k], s.ks = ks[k], s.ktor = ktor[k], s.kben = kben[k];
  s.contact_fraction = contact_fraction[k], s.radius = radius[k];
  return s;
}

std::size_t BondStore::memory_bytes() const
{
  auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return bytes(a) + bytes(b) + bytes(rest_length) + bytes(rest_axis) + bytes(kn) + bytes(ks) +
         bytes(ktor) + bytes(kben) + bytes(contact_fraction) + bytes(radius) +
         bytes(damping_force) + bytes(damping_moment) + bytes(model) + bytes(state) +
         bytes(bond_class) + bytes(basal_normal) + bytes(force) + bytes(moment) +
         bytes(tensile_strength) + bytes(shear_strength) + bytes(damage) + bytes(kappa_max) +
         bytes(kappa_ultimate) + bytes(dissipated) + bytes(failure_mode);
}
} // namespace dembridge::dem
