#pragma once
// The failure index of a handshake band's bond: its force and moment as the full bond carries
// them (the band's blended share divided out), against its class's strength constants,
//   kappa = max(sigma / sigma_t, tau / tau_max(sigma_n)),
// which the bond breaks at (dem/bonds/bond_stress.h, bond_damage.h). The one-process and the
// ranks' band checks both read it.
#include "dem/bonds/bond_store.h"
#include "dem/bonds/bond_stress.h"
#include <algorithm>

namespace dembridge::coupling
{
/// Bond k of @p b along @p chord (from end a to end b) with the full bond's @p force and
/// @p moment, against @p tensile strength and @p shear strength (Pa).
inline double band_failure_index(const dem::BondStore& b, std::size_t k, const dem::Vec3& chord,
                                 const dem::Vec3& force, const dem::Vec3& moment, double tensile,
                                 double shear)
{
  const dem::Vec3 e = chord.normalized();
  const dem::FailureConstants& constants = b.failure_constants(k); // its class's
  const auto s =
      dem::bond_stress(force.data(), moment.data(), e.data(), b.radius[k], constants.moment_factor);
  const double tau_max =
      dem::shear_strength(b.failure.shear, constants, shear, s.normal_force, s.area);
  return std::max(s.tensile / tensile, s.shear / tau_max);
}
} // namespace dembridge::coupling
