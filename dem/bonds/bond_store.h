#pragma once
// Bond storage: structure of arrays. A bond joins particles a < b; its constants are fixed at
// formation; its state can flip from intact to broken (bonds are never erased inside the force
// loop, so indices stay valid for output and the later damage model).
#include "dem/bonds/bond_model.h"
#include <vector>

namespace dembridge::dem
{
enum class BondState : std::uint8_t
{
  intact,
  broken,
};

struct BondStore
{
  std::vector<std::int32_t> a, b;
  std::vector<double> rest_length; ///< L_0, m
  std::vector<Vec3> rest_axis;     ///< e_0 (unit, a -> b) at formation, global = body frame
  std::vector<double> kn, ks, ktor, kben, contact_fraction, radius;
  std::vector<double> damping_force;  ///< c_t, N·s/m (thesis eq. 35-37)
  std::vector<double> damping_moment; ///< c_r, N·m·s/rad (paper eq. 10, same scaling)
  std::vector<BondModel> model;
  std::vector<BondState> state;
  // Last recorded contact-point force and couple acting on particle b (global frame); filled
  // on recording steps only (output, energy), not on every step.
  std::vector<Vec3> force, moment;

  std::size_t size() const { return a.size(); }
  /// The constants of bond k as formed (inverse of add's BondStiffness argument).
  BondStiffness stiffness(std::size_t k) const;
  void add(std::int32_t ia, std::int32_t ib, double length, const Vec3& axis, BondModel m,
           const BondStiffness& k);
};
} // namespace dembridge::dem
