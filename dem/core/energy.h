#pragma once
// Energy bookkeeping (thesis section 3.5, eq. 49-53), extended by the terms of damage and
// contacts:
//   W_kin       kinetic energy of translation and rotation (eq. 49)
//   W_strain    elastic energy stored in intact (and softening) bonds (closed form of the
//               unified law, cf. eq. 50)
//   W_damp      energy dissipated by bond dashpots (eq. 51) and particle damping (paper eq. 11-12)
//   W_ext       work of applied forces and of supports with prescribed motion (eq. 52)
//   W_frac      strain energy released by breaking bonds and dissipated by bond softening
//   W_cstrain   elastic energy stored in particle-particle and particle-wall contacts
//   W_fric      energy dissipated by Coulomb sliding and rolling resistance
//   W_cdamp     energy dissipated by contact dashpots
//   W_wall      work of moving walls (and other boundaries acting through contacts) on particles
// Balance (eq. 53 extended):
//   W_kin + W_strain + W_cstrain + W_damp + W_frac + W_fric + W_cdamp = W_ext + W_wall + W_0
// with W_0 the kinetic and stored energy at t = 0; the error is reported relative to the largest
// component.
#include <algorithm>
#include <cmath>

namespace dembridge::dem
{
struct EnergyBalance
{
  double kinetic = 0, strain = 0, damping = 0, external = 0;
  double initial = 0; ///< kinetic + stored energy at t = 0 (initial velocities)
  double fracture = 0;
  double contact_strain = 0, friction = 0, contact_damping = 0, wall_work = 0;

  /// Energy stored and dissipated inside the system (the left-hand side of the balance).
  double internal() const
  {
    return kinetic + strain + contact_strain + damping + fracture + friction + contact_damping;
  }
  double error() const { return std::abs(internal() - external - wall_work - initial); }
  double largest() const
  {
    return std::max({std::abs(kinetic), std::abs(strain), std::abs(damping), std::abs(external),
                     std::abs(initial), std::abs(fracture), std::abs(contact_strain),
                     std::abs(friction), std::abs(contact_damping), std::abs(wall_work)});
  }
  double relative_error() const { return largest() > 0 ? error() / largest() : 0.0; }
};
} // namespace dembridge::dem
