#pragma once
// Linear spring-dashpot contact (thesis eq. 12-13; Cundall & Strack 1979):
//   F_n = k_n delta + c_n d(delta)/dt                                        eq. (12)
//   F_t = -k_t xi  (xi: tangential spring, |k_t xi| <= mu F_n, Coulomb)        eq. (13)
// with the dashpots set from the restitution coefficient e (Chung & Ooi 2011; Ting & Corkum):
//   c_n = 2 zeta sqrt(m* k_n),  c_t = 2 zeta sqrt(m* k_t),  zeta = -ln e / sqrt(pi^2 + ln^2 e)
// For a free pair this returns exactly e at the moment the overlap is back to zero (the force is
// not clipped at zero, so the dashpot may pull briefly at the end of the contact; clipping would
// raise the rebound above e).
// Stored energy of the normal spring: 1/2 k_n delta^2.
// Units: delta m, k N/m, c N·s/m, m* kg, R* m.
#include <cmath>

namespace dembridge::dem
{
struct LinearSpringDashpot
{
  double kn = 0;   ///< N/m
  double kt = 0;   ///< N/m
  double zeta = 0; ///< damping ratio of both dashpots

  struct Response
  {
    double force;     ///< elastic normal force, N
    double stiffness; ///< tangent normal stiffness dF/d(delta), N/m
    double energy;    ///< normal strain energy, J
    double cn, kt, ct;
  };

  Response operator()(double delta, double /*r_eff*/, double m_eff) const
  {
    const double damp = 2.0 * zeta * std::sqrt(m_eff);
    return {kn * delta,           kn, 0.5 * kn * delta * delta,
            damp * std::sqrt(kn), kt, damp * std::sqrt(kt)};
  }
};
} // namespace dembridge::dem
