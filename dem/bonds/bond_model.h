#pragma once
// The three bond models of Chen et al. (2022) in their unified form (paper Tables 8 and 9).
// Every model is the same kernel (bond_kernel.h); a model is only
//   (a) where the contact point lies on the bond axis, and
//   (b) how the four stiffnesses k_n, k_s, k_tor, k_ben follow from the bond material.
//
//   contact point   PBM:  x_c = x_a + 0.5 (L_b + R_a - R_b) e        (Table 9)
//                   EBBM, TBBM: x_c = x_a + 0.5 L_b e                 (eq. 44)
//   k_n   = E_b A_b / L_b                  all models (Table 9), A_b = pi r_b^2 (eq. 23)
//   k_s   = k_n / kappa                    PBM (Table 1; kappa = 2 (1 + nu_b), eq. 8, by default)
//         = 12 E_b I_b / L_b^3             EBBM (eq. 26)
//         = 12 E_b I_b / (L_b^3 (1+Phi))   TBBM (eq. 18), Phi = 20 r_b^2 (1+nu_b) / (3 L_b^2) (eq.
//         25)
//   k_tor = 0.5 k_s r_b^2                  PBM (Table 1)
//         = 0.25 k_n r_b^2 / (1 + nu_b)    EBBM, TBBM (Table 6)
//   k_ben = 0.25 k_n r_b^2                 all models
// Units: k_n, k_s in N/m; k_tor, k_ben in N·m/rad.
// The thesis' parallel bond is given per unit area (k̄_n in Pa/m, k̄_n / k̄_s = kappa; thesis
// eq. 10-11, 16-17): k_n = k̄_n A_b. That is the PBM with a user-given normal stiffness.
#include "dem/core/types.h"
#include <array>
#include <string_view>

namespace dembridge::dem
{
enum class BondModel : std::uint8_t
{
  parallel_bond,   ///< Itasca/Potyondy–Cundall parallel bond (PBM)
  euler_bernoulli, ///< Euler–Bernoulli beam bond (EBBM)
  timoshenko,      ///< Timoshenko beam bond (TBBM)
};

/// The names a user types in a case file, in enum order. One registry gives the parser and the
/// Patterns::Selection string.
inline constexpr std::array<std::string_view, 3> bond_model_names = {
    {"parallel_bond", "euler_bernoulli", "timoshenko"}};

BondModel bond_model_from_name(std::string_view name);
std::string bond_model_selection(); ///< "parallel_bond|euler_bernoulli|timoshenko"

/// Material of all bonds of a specimen.
struct BondMaterial
{
  BondModel model = BondModel::timoshenko;
  double youngs_modulus = 0.0;            ///< E_b, Pa
  double poisson_ratio = 0.3;             ///< nu_b, in (-1, 0.5)
  double radius_multiplier = 1.0;         ///< r_b = multiplier * min(R_a, R_b)
  double stiffness_ratio = 0.0;           ///< PBM kappa = k_n/k_s; 0: 2 (1 + nu_b) (paper eq. 8)
  double normal_stiffness_per_area = 0.0; ///< PBM k̄_n in Pa/m; 0: E_b / L_b

  /// Throws InputError naming `section` if a value is non-physical.
  void validate(const std::string& section) const;
};

/// Per-bond constants of the unified law.
struct BondStiffness
{
  double kn = 0, ks = 0, ktor = 0, kben = 0;
  double contact_fraction = 0.5; ///< s: x_c = x_a + s L_b e
  double radius = 0;             ///< r_b
};

/// Stiffness and contact point of a bond of length L (m) between spheres of radii ra, rb.
BondStiffness bond_stiffness(const BondMaterial& mat, double length, double ra, double rb);
} // namespace dembridge::dem
