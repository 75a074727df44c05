#pragma once
// Energy bookkeeping (thesis section 3.5):
//   W_kin    kinetic energy of translation and rotation (eq. 49)
//   W_strain elastic energy stored in intact bonds (closed form of the unified law, cf. eq. 50)
//   W_damp   energy dissipated by bond dashpots (eq. 51) and particle damping (paper eq. 11-12)
//   W_ext    work of applied forces and of supports with prescribed motion (eq. 52)
// Balance error (eq. 53): |W_kin + W_strain + W_damp - W_ext|, reported relative to the largest
// component.
#include <algorithm>
#include <cmath>

namespace dembridge::dem
{
struct EnergyBalance
{
  double kinetic = 0, strain = 0, damping = 0, external = 0;
  double initial = 0; ///< kinetic + strain energy at t = 0 (initial velocities)

  double error() const { return std::abs(kinetic + strain + damping - external - initial); }
  double largest() const
  {
    return std::max({std::abs(kinetic), std::abs(strain), std::abs(damping), std::abs(external),
                     std::abs(initial)});
  }
  double relative_error() const { return largest() > 0 ? error() / largest() : 0.0; }
};
} // namespace dembridge::dem
