#pragma once
// Hertz-Mindlin (no-slip) contact with Tsuji damping, as in EDEM and Chung & Ooi (2011):
//   F_n = 4/3 E* sqrt(R*) delta^(3/2)                        Hertz (Johnson 1985, section 4.2)
//   S_n = dF_n/d(delta) = 2 E* sqrt(R* delta)
//   k_t = S_t = 8 G* sqrt(R* delta)                          Mindlin (1949), no slip
//   c_n = -2 sqrt(5/6) beta sqrt(S_n m*),  c_t = -2 sqrt(5/6) beta sqrt(S_t m*)
//   beta = ln e / sqrt(ln^2 e + pi^2)                        (Tsuji et al. 1992; EDEM manual)
// Effective constants for two spheres i, j (or a sphere and a rigid wall: drop the wall's terms):
//   1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j,   1/G* = (2 - nu_i)/G_i + (2 - nu_j)/G_j,
//   G = E / (2 (1 + nu)),  1/R* = 1/R_i + 1/R_j,  1/m* = 1/m_i + 1/m_j.
// Stored energy of the normal spring: 8/15 E* sqrt(R*) delta^(5/2) = 2/5 F_n delta.
// Chung & Ooi's closed forms (the tests): delta_max = (15 m* v^2 / (16 E* sqrt R*))^(2/5),
// t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5) for an elastic impact at relative speed v.
// Units: E*, G* Pa; delta, R* m; m* kg.
#include <cmath>

namespace dembridge::dem
{
struct HertzMindlin
{
  double e_eff = 0; ///< E*, Pa
  double g_eff = 0; ///< G*, Pa
  double beta = 0;  ///< ln e / sqrt(ln^2 e + pi^2) (<= 0)

  struct Response
  {
    double force;     ///< elastic normal force, N
    double stiffness; ///< S_n, N/m
    double energy;    ///< normal strain energy, J
    double cn, kt, ct;
  };

  Response operator()(double delta, double r_eff, double m_eff) const
  {
    const double a = std::sqrt(r_eff * delta); // contact radius
    const double sn = 2.0 * e_eff * a;
    const double st = 8.0 * g_eff * a;
    const double force = (2.0 / 3.0) * sn * delta; // = 4/3 E* sqrt(R*) delta^(3/2)
    const double damp = -2.0 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(m_eff);
    return {force, sn, 0.4 * force * delta, damp * std::sqrt(sn), st, damp * std::sqrt(st)};
  }
};
} // namespace dembridge::dem
