#pragma once
// A specimen's microstructure: grains (columnar_grains.h), weak planes (weak_planes.h) and the
// bond classes they give (bonds/bond_class.h). Off by default: without grains and planes every
// bond is formed from the Bonds and Damage values, as in a homogeneous specimen.
//
// Each bond, once formed, is classed by the particles it joins:
//   weak_plane      its axis crosses a weak plane (whatever the grains)
//   grain_boundary  otherwise, its particles lie in two grains
//   basal           otherwise, with a basal cone: its axis at formation e_0 lies within the
//                   cone's half-angle theta_b of its grain's c-axis c, |e_0 . c| >= cos theta_b
//   intra_grain     otherwise
// and takes its class's constants: the stiffnesses and contact point of bond_model.h from the
// class's bond material, its strengths drawn around the class's means (bond_strength.h), and its
// friction angle, moment factor and fracture energies (bond_damage.h FailureConstants; the
// failure mode and shear criterion are the specimen's). Intra-grain bonds are the Bonds and
// Damage values; every class value defaults to them. A class only picks per-bond constants at
// formation: the force loops read them as they read a homogeneous specimen's (the failure
// constants through the class byte, from a table of four).
//
// Basal bonds: ice deforms by slip on its basal planes (normal c) far more easily than by any
// other system (Schulson & Duval 2009, Creep and Fracture of Ice, ch. 5), so a grain's interior
// is weak in shear on its basal planes. The bonds that cross them nearly normally (near c) take
// that weakness: a class of their own (its stiffness and strengths), optionally smooth joints
// whose normal is the grain's c-axis (bonds/smooth_joint.h), which shear by the relative
// displacement along the basal plane whatever their axis. Columnar ice has its c-axes across the
// columns, so a load along the columns lies in every basal plane (no resolved shear), while a
// load across them shears the basal planes of grains whose c-axis is inclined to it.
//
// Springs in series (the check, tests/dem/test_microstructure.cc): on the simple cubic
// lattice with spacing d, planes normal to x every n layers whose bonds are alpha times as
// stiff leave each x-chain of N bonds with N/n weak ones, so
//   1/E_x = (1/E) (1 - 1/n + 1/(alpha n)),   E_y = E_z = E                                  (1)
// exactly (the lattice has no Poisson coupling: the y- and z-bonds do not deform in uniaxial
// strain along x, and the planes cross no y- or z-bond).
#include "dem/bonds/bond_store.h"
#include "dem/bonds/bond_strength.h"
#include "dem/core/particle_store.h"
#include "dem/microstructure/columnar_grains.h"
#include "dem/microstructure/weak_planes.h"
#include <array>
#include <optional>

namespace dembridge::dem
{
/// The Bonds and Damage values of one bond class.
struct BondClassConfig
{
  BondMaterial material;
  double tensile_strength = 0;   ///< sigma_t, Pa (mean)
  double shear_strength = 0;     ///< tau_c, Pa (mean; constant criterion)
  double cohesion = 0;           ///< c, Pa (mean; Mohr-Coulomb)
  double friction_angle = 0;     ///< phi, degrees (Mohr-Coulomb)
  double moment_factor = 1;      ///< beta in [0, 1] (bond_stress.h)
  double fracture_energy_I = 0;  ///< G_f, J/m^2, tension governs (softening)
  double fracture_energy_II = 0; ///< G_f, J/m^2, shear governs (softening)

  /// The intra-grain values: the Bonds material and the Damage means.
  static BondClassConfig of_specimen(const BondMaterial& material, const DamageConfig& damage);
};

struct MicrostructureConfig
{
  ColumnarGrainsConfig grains;
  std::optional<WeakPlaneSet> weak_planes;
  /// Grain-boundary, weak-plane and basal bonds; unset: the Bonds and Damage values.
  std::optional<BondClassConfig> grain_boundary, weak_plane, basal;
  /// Half-angle theta_b of the basal cone about each grain's c-axis, degrees; 0: no basal bonds.
  double basal_cone = 0;
  /// The basal bonds are smooth joints whose normal is their grain's c-axis.
  bool basal_smooth_joint = false;
  /// The weak-plane bonds are smooth joints (bonds/smooth_joint.h) across the planes.
  bool smooth_joint = false;
  /// With smooth_joint: mu_j of the pairs across the planes once unbonded
  /// (contacts/joint_contact.h).
  double joint_friction = 0.5;
  /// With a value mu_gb: pairs of particles in two grains whose bond is broken, or that have
  /// none, meet as unbonded smooth joints on their grains' boundary (bonds/sliding_joints.h,
  /// contacts/joint_contact.h) with friction mu_gb; unset: they meet as spheres.
  std::optional<double> boundary_joint_friction;

  bool enabled() const { return grains.enabled || weak_planes.has_value(); }
};

/// Every class's values (intra-grain from @p material and @p damage, the others from the config
/// or, where unset, the same), checked: the bond material (section "Bond class NAME") and, when
/// @p damage has a failure law, positive strengths. Throws InputError naming Section/key.
std::array<BondClassConfig, bond_class_count> bond_class_configs(const MicrostructureConfig& config,
                                                                 const BondMaterial& material,
                                                                 const DamageConfig& damage);

/// What each class fails by, for assign_bond_strengths: its strength means by the shear
/// criterion of @p damage, and its failure constants.
std::array<ClassDamage, bond_class_count>
class_damage(const std::array<BondClassConfig, bond_class_count>& classes,
             const DamageConfig& damage);

/// What the microstructure gave a specimen: the grains (their seeds and c-axes), bond counts
/// per class.
struct MicrostructureSummary
{
  std::vector<Grain> grains;
  std::size_t columns = 0;
  std::array<std::size_t, bond_class_count> bonds_per_class{};
};

/// Assigns the grains (p.grain) and classes the bonds just formed (bonds.bond_class), giving
/// each non-intra-grain bond its class's stiffness constants (and with config.smooth_joint the
/// store the planes' normal, bonds.smooth_joint_normal) (strengths follow in
/// assign_bond_strengths with class_damage; with config.basal_smooth_joint each basal
/// bond's c-axis, bonds.basal_normal). Throws InputError naming the key when the grains or planes
/// do not fit the packing (column_grains.h, weak_planes.h) or a plane crosses no bond.
MicrostructureSummary
apply_microstructure(ParticleStore& p, BondStore& bonds, const MicrostructureConfig& config,
                     const std::array<BondClassConfig, bond_class_count>& classes);
} // namespace dembridge::dem
