#pragma once
// Bond failure: the failure index of a bond and its damage, brittle or by linear softening to a
// fracture energy (after Potyondy & Cundall 2004 for the strengths, and the bilinear
// softening parallel bond of Kratos/DEMpack for the energy regularisation).
//
// Failure index (bond_stress.h for sigma, tau; evaluated on the undamaged "trial" forces):
//   kappa = max(sigma / sigma_t, tau / tau_max)                                         (1)
//   tau_max = tau_c                                  constant shear strength
//           = c + sigma_c tan(phi),  sigma_c = max(0, -F_n / A)   Mohr-Coulomb           (2)
// Brittle: the bond breaks in the step kappa reaches 1; from that step on it carries nothing.
// Softening: with kappa_hat the largest kappa reached so far, the effective ratio
// (1 - D) kappa_hat falls linearly from 1 at kappa_hat = 1 to 0 at kappa_u:
//   D = 0                                                     kappa_hat <= 1
//     = 1 - (kappa_u - kappa_hat) / ((kappa_u - 1) kappa_hat)  1 < kappa_hat < kappa_u      (3)
//     = 1                                                     kappa_hat >= kappa_u
// and the bond's forces and dashpots are the trial ones times (1 - D) (secant unloading).
// Under proportional loading kappa is proportional to the deformation and the trial energy is
// U_e = U_peak kappa^2, so the force-deformation curve is a triangle: linear up to the peak
// (U_peak stored), linear down to zero at kappa_u times the peak deformation. Its area, all of it
// dissipated once D = 1, is U_peak kappa_u; equating it to G_f A gives
//   kappa_u = G_f A / U_peak                                                                (4)
// with G_f the fracture energy of the mode that governs (1) when softening starts (mode I:
// tension, mode II: shear), J/m^2 of bond area. U_peak is the trial energy at the start of
// softening scaled to kappa = 1 (U_e / kappa^2), so the dissipated energy is G_f A whatever the
// time step or particle size. kappa_u < 1 would be snap-back (the descending branch bending back):
// setup refuses G_f A below the peak energy of pure tension sigma_t^2 A^2 / (2 k_n) or of pure
// shear tau_c^2 A^2 / (2 k_s) (bond_strength.h); under a mixed load whose peak energy still exceeds
// G_f A, kappa_u is held at 1 and the bond fails brittly (its energy is booked all the same).
// Dissipation: the stored energy is (1 - D) U_e, the forces do the work (1 - D) dU_e, so
// softening dissipates U_e dD >= 0 (fracture energy, dem/core/energy.h). In the leapfrog scheme
// the step n's increment is booked as
//   dW_frac = dD (U_e(x^n) + 1/2 dt P_e)                                                    (5)
// with P_e the power of the trial elastic forces on the two particles at the velocities
// v^{n-1/2}, w^{n-1/2}: the change of the scheme's conserved (time-centred) energy when the bond's
// stiffness drops by dD at step n, so the balance of thesis eq. 53 closes to round-off for linear
// bonds through softening and breaking. A brittle break is (5) with dD = 1.
// Bond classes (bond_class.h) may each have their own phi, beta and G_f (FailureConstants): a
// bond reads its class's in (1)-(4); the mode and the shear criterion are the store's.
#include "dem/bonds/bond_class.h"
#include "dem/core/types.h"
#include <algorithm>
#include <array>
#include <cstdint>

namespace dembridge::dem
{
enum class FailureMode : std::uint8_t
{
  none,     ///< bonds never fail
  brittle,  ///< gone in the step the failure index reaches 1
  softening ///< linear softening to the fracture energy
};

enum class ShearCriterion : std::uint8_t
{
  constant,    ///< tau_max = tau_c
  mohr_coulomb ///< tau_max = c + sigma_c tan(phi)
};

/// The constants of the failure law that a bond class may set for itself (bond_class.h).
struct FailureConstants
{
  double tan_friction = 0;       ///< tan(phi), Mohr-Coulomb
  double moment_factor = 1;      ///< beta in [0, 1] (bond_stress.h)
  double fracture_energy_I = 0;  ///< G_f, J/m^2, tension governs (softening)
  double fracture_energy_II = 0; ///< G_f, J/m^2, shear governs (softening)
};

/// Failure law of the bonds of one material (the per-bond strengths are in BondStore): the
/// mode and shear criterion of every bond; its own constants are those of a store without
/// classes (and of the intra-grain bonds).
struct FailureLaw : FailureConstants
{
  FailureMode mode = FailureMode::none;
  ShearCriterion shear = ShearCriterion::constant;
  /// With by_class, a store with classes reads each bond's constants here by its class (a
  /// table of four, not a copy per bond: the class byte is the per-bond value).
  std::array<FailureConstants, bond_class_count> classes{};
  bool by_class = false;
};

/// Which stress governed a failure.
enum class CrackMode : std::uint8_t
{
  tension,
  shear
};

/// One bond failure, as the explicit solver logs it.
struct CrackEvent
{
  double time = 0;              ///< s
  std::size_t bond = 0;         ///< index in the BondStore (solver order)
  int a = 0, b = 0;             ///< the particles' user ids (ParticleStore::id)
  Vec3 midpoint = Vec3::Zero(); ///< between the particle centres at failure, m
  Vec3 axis = Vec3::UnitX();    ///< unit, a -> b, at failure (a smooth joint: its plane's normal)
  CrackMode mode = CrackMode::tension;
  double energy = 0; ///< J: strain energy released (brittle) or dissipated in softening
};

/// Shear strength of eq. (2) at the tensile normal force F_n (N) on the area A, with the
/// constants @p k (a bond class's, or the law's own).
inline double shear_strength(ShearCriterion criterion, const FailureConstants& k, double strength,
                             double normal_force, double area)
{
  if (criterion == ShearCriterion::constant)
    return strength;
  return strength + std::max(0.0, -normal_force / area) * k.tan_friction; // eq. (2)
}

/// Shear strength of eq. (2) with the law's own constants.
inline double shear_strength(const FailureLaw& law, double strength, double normal_force,
                             double area)
{
  return shear_strength(law.shear, law, strength, normal_force, area);
}

/// Damage of eq. (3) at the largest failure index kappa_hat reached.
inline double softening_damage(double kappa_hat, double kappa_u)
{
  if (kappa_hat <= 1.0)
    return 0.0;
  if (kappa_hat >= kappa_u)
    return 1.0;
  return 1.0 - (kappa_u - kappa_hat) / ((kappa_u - 1.0) * kappa_hat); // eq. (3)
}
} // namespace dembridge::dem
