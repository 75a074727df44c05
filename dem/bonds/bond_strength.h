#pragma once
// Bond strengths and the damage settings of a case (`Damage` section of a case file).
//
// Each bond gets a tensile strength sigma_t and a shear strength (the constant tau_c, or the
// cohesion c of the Mohr-Coulomb criterion; bond_damage.h eq. 2), both in Pa. They are the given
// means, or scattered between bonds (seeded, deterministic; two independent draws per bond, in
// the order the bonds were formed):
//   normal   s = s_mean (1 + delta z),  z ~ N(0, 1) (Box-Muller), redrawn while s <= 0
//            (a normal distribution truncated to positive strengths; delta = relative std dev)
//   weibull  s = lambda (-ln(1 - u))^(1/m),  u ~ U[0, 1),  lambda = s_mean / Gamma(1 + 1/m)
//            (Weibull modulus m; the mean is s_mean)
// The generator is std::mt19937_64 with uniforms built from its raw 53 bits, so the same seed
// gives bit-identical strengths on every platform.
// Keyed by position (`scatter key = position`), each bond draws from a generator of its own,
// seeded by the seed and its reference midpoint on a 0.1 um grid (splitmix64 of the three
// grid indices): a bond's strengths then depend on where it is, not on the order the bonds were
// formed in, so a packing renumbered, or the same lattice in a larger specimen (the particle
// region of a coupled run and its full-DEM counterpart, `dembridge compare`), gives every
// bond the same strengths.
// Softening (bond_damage.h eq. 4) needs kappa_u >= 1 for every bond: G_f A is at least the
// elastic energy at the peak of pure tension, sigma_t^2 A^2 / (2 k_n) (mode I), and of pure shear,
// tau_c^2 A^2 / (2 k_s) (mode II; Mohr-Coulomb: c, the strength without compression). Setup
// refuses anything less (snap-back), naming the largest energy a bond needs.
#include "dem/bonds/bond_store.h"
#include <span>
#include <string>

namespace dembridge::dem
{
enum class StrengthScatter : std::uint8_t
{
  none,
  normal,
  weibull
};

/// The `Damage` section of a case: failure law, mean strengths and their scatter.
struct DamageConfig
{
  FailureLaw law; ///< mode, shear criterion, tan(phi), moment factor, fracture energies
  double tensile_strength = 0; ///< sigma_t, Pa (mean)
  double shear_strength = 0;   ///< tau_c, Pa (mean; constant criterion)
  double cohesion = 0;         ///< c, Pa (mean; Mohr-Coulomb)
  double friction_angle = 0;   ///< phi, degrees (Mohr-Coulomb); law.tan_friction follows
  StrengthScatter scatter = StrengthScatter::none;
  double scatter_deviation = 0; ///< relative std dev (normal)
  double weibull_modulus = 0;   ///< m (weibull)
  unsigned long seed = 1;
  bool scatter_by_position = false; ///< key each bond's draws by its reference midpoint

  /// Throws InputError naming Damage/key when a value is non-physical (a no-op for mode none).
  void validate() const;
};

/// What a bond class (bond_class.h) fails by: its mean strengths, Pa (sigma_t, and tau_c or c
/// as the shear criterion has it), and its failure constants (tan phi, moment factor, fracture
/// energies).
struct ClassDamage
{
  double tensile = 0, shear = 0;
  FailureConstants law;
};

/// Sets the store's failure law and every bond's strengths (and resets its damage); checks the
/// softening fracture energies against snap-back. Throws InputError naming Damage/key.
/// @p positions: the particles' reference positions, needed by scatter_by_position.
/// @p classes: per bond class, the means a bond of that class draws around (the scatter is
/// relative, so a bond's draw is its class mean times the draw of the config's own) and the
/// constants it fails by (the store's failure.classes; the snap-back check per class); empty or
/// a store without classes: the config's means and constants for every bond.
void assign_bond_strengths(BondStore& bonds, const DamageConfig& config,
                           const std::vector<Vec3>* positions = nullptr,
                           std::span<const ClassDamage> classes = {});
} // namespace dembridge::dem
