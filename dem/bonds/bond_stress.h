#pragma once
// Bond stresses from beam theory on the bond's circular cross-section (Potyondy & Cundall 2004,
// Int. J. Rock Mech. Min. Sci. 41, eq. 9-10; the parallel bond's maximum stresses at its
// periphery), for every bond model of the unified law (bond_kernel.h):
//   sigma = F_n / A + beta |M_b| R_b / I        maximum tensile stress, tension positive
//   tau   = |F_s| / A + beta |M_t| R_b / J      maximum shear stress
//   A = pi R_b^2,  I = pi R_b^4 / 4,  J = pi R_b^4 / 2
// with F_n = -F_c . e the tensile normal force (F_c, the contact force on particle b, points
// back towards a when the bond is stretched), F_s = F_c - (F_c . e) e the shear force,
// M_t = (M_c . e) e the twisting and M_b = M_c - M_t the bending couple at the contact point,
// e the bond axis a -> b, R_b the bond radius, and beta in [0, 1] PFC's moment-contribution
// factor (beta = 1: full beam theory; Itasca's linear parallel bond, "mcf").
// Evaluated at the bond's contact point (PFC's convention: the parallel bond's contact lies at
// the contact plane; the beam bonds' at the bond centre, where the bending moment of a beam
// loaded at its ends is the mean of the end moments). Units: N, N·m, m -> Pa.
#include <cmath>
#include <numbers>

namespace dembridge::dem
{
/// The section's loads in the form the failure check reads them, free of divisions: with
/// R/I = 4 / (A R) and R/J = 2 / (A R),
///   sigma A R = R F_n + 4 beta |M_b|,   tau A R = R |F_s| + 2 beta |M_t|      (N·m)
/// so sigma >= sigma_t  <=>  tension >= sigma_t A R, and likewise for tau.
struct SectionLoads
{
  double normal_force = 0; ///< F_n, N (tension positive)
  double tension = 0;      ///< sigma A R, N·m
  double shear = 0;        ///< tau A R, N·m
};

inline SectionLoads section_loads(const double* F, const double* M, const double* e, double radius,
                                  double moment_factor)
{
  const double fe = F[0] * e[0] + F[1] * e[1] + F[2] * e[2];
  const double me = M[0] * e[0] + M[1] * e[1] + M[2] * e[2];
  const double fsx = F[0] - fe * e[0], fsy = F[1] - fe * e[1], fsz = F[2] - fe * e[2];
  const double mbx = M[0] - me * e[0], mby = M[1] - me * e[1], mbz = M[2] - me * e[2];
  SectionLoads l;
  l.normal_force = -fe;
  l.tension =
      radius * l.normal_force + 4.0 * moment_factor * std::sqrt(mbx * mbx + mby * mby + mbz * mbz);
  l.shear =
      radius * std::sqrt(fsx * fsx + fsy * fsy + fsz * fsz) + 2.0 * moment_factor * std::abs(me);
  return l;
}

struct BondStress
{
  double tensile = 0;      ///< sigma, Pa (tension positive)
  double shear = 0;        ///< tau, Pa (>= 0)
  double normal_force = 0; ///< F_n, N (tension positive)
  double area = 0;         ///< A, m^2
};

/// Stresses of a bond of radius R_b from its contact force F and couple M on particle b (global
/// frame) and its current axis e (unit, a -> b).
inline BondStress bond_stress(const double* F, const double* M, const double* e, double radius,
                              double moment_factor)
{
  const SectionLoads l = section_loads(F, M, e, radius, moment_factor);
  BondStress s;
  s.area = std::numbers::pi * radius * radius;
  s.normal_force = l.normal_force;
  s.tensile = l.tension / (s.area * radius);
  s.shear = l.shear / (s.area * radius);
  return s;
}
} // namespace dembridge::dem
