#pragma once
// Bond storage: structure of arrays. A bond joins particles a < b; its constants are fixed at
// formation; its state goes from intact to softening (damaged, still carrying (1 - D) of its
// trial forces) to broken, never back (bonds are never erased inside the force loop, so indices
// stay valid for output and the crack log). Strengths and damage (bond_damage.h) are per bond;
// their arrays are empty when the failure law is `none`.
#include "dem/bonds/bond_class.h"
#include "dem/bonds/bond_damage.h"
#include "dem/bonds/bond_model.h"
#include "dem/bonds/sliding_joints.h"
#include <optional>
#include <vector>

namespace dembridge::dem
{
enum class BondState : std::uint8_t
{
  intact,
  softening, ///< damaged (0 < D < 1): bonded, carries (1 - D) of its trial forces
  broken,    ///< carries nothing, never again (a broken pair is not re-bonded)
};

/// A bond that still joins its particles (intact or softening): it carries forces, and its pair
/// is no contact pair.
inline bool is_bonded(BondState s)
{
  return s != BondState::broken;
}

struct BondStore
{
  std::vector<std::int32_t> a, b;
  std::vector<double> rest_length; ///< L_0, m
  std::vector<Vec3> rest_axis;     ///< e_0 (unit, a -> b) at formation, global = body frame
  std::vector<double> kn, ks, ktor, kben, contact_fraction, radius;
  std::vector<double> damping_force;  ///< c_t, N·s/m (thesis eq. 35-37)
  std::vector<double> damping_moment; ///< c_r, N·m·s/rad (paper eq. 10, same scaling)
  std::vector<BondModel> model;
  std::vector<BondState> state;
  /// The class that chose each bond's constants (bond_class.h); empty without a microstructure
  /// (every bond intra-grain).
  std::vector<BondClass> bond_class;
  /// With a value N (unit), the weak-plane bonds are smooth joints across planes of normal N
  /// (bonds/smooth_joint.h); unset: every bond follows the unified law (bond_kernel.h).
  std::optional<Vec3> smooth_joint_normal;
  /// With basal joints: per bond, the unit normal a basal bond resolves its force against (its
  /// grain's c-axis, bonds/smooth_joint.h); read for the basal bonds only. Empty: the basal
  /// bonds, if any, follow the unified law.
  std::vector<Vec3> basal_normal;
  /// With a value, the pairs across the smooth joints' planes meet as unbonded joints once
  /// their bond is broken or where they have none (contacts/joint_contact.h): the planes and
  /// the joints' friction. Unset: they meet as spheres (contacts/contact_kernel.h).
  std::optional<SlidingJoints> sliding_joints;
  // Last recorded contact-point force and couple acting on particle b (global frame); filled
  // on recording steps only (the static run's figures, a coupled run's band check, the tests
  // of the force loop), not on every step. 48 of the 154 bytes of a bond: explicit full-DEM
  // runs drop them before the bonds are formed (their ParaView bond files evaluate each bond
  // on demand, bond_contact_force in particle_stress.h), and then they stay empty.
  std::vector<Vec3> force, moment;
  bool force_records_dropped = false; ///< set by drop_force_records: add() keeps none

  // Failure (bond_damage.h, bond_strength.h): one law for the store, strengths and damage per
  // bond (filled by assign_bond_strengths; empty while failure.mode is none).
  FailureLaw failure;
  std::vector<double> tensile_strength; ///< sigma_t, Pa
  std::vector<double> shear_strength;   ///< tau_c (constant) or cohesion c (Mohr-Coulomb), Pa
  std::vector<double> damage;           ///< D in [0, 1] (1 once broken)
  std::vector<double> kappa_max;        ///< largest failure index above 1 reached (softening)
  std::vector<double> kappa_ultimate;   ///< kappa_u, fixed when softening starts (eq. 4)
  std::vector<double> dissipated;       ///< fracture energy booked for the bond so far, J
  std::vector<CrackMode> failure_mode;  ///< mode that governed when softening started

  std::size_t size() const { return a.size(); }
  /// Whether force / moment are kept (one entry per bond).
  bool records_forces() const { return !force_records_dropped && force.size() == a.size(); }
  /// Frees force / moment; add() then no longer fills them (also on a store still empty, so
  /// that bond formation never holds them).
  void drop_force_records()
  {
    force = {}, moment = {};
    force_records_dropped = true;
  }
  bool has_failure() const { return failure.mode != FailureMode::none; }
  /// Whether the weak-plane bonds are smooth joints.
  bool has_plane_joints() const { return smooth_joint_normal.has_value() && !bond_class.empty(); }
  /// Whether the basal bonds are smooth joints.
  bool has_basal_joints() const { return !basal_normal.empty() && !bond_class.empty(); }
  /// Whether any bond may be a smooth joint (the force loop's joint instantiation).
  bool has_smooth_joints() const { return has_plane_joints() || has_basal_joints(); }
  /// Whether bond k is a smooth joint.
  bool is_smooth_joint(std::size_t k) const { return joint_normal(k) != nullptr; }
  /// The plane normal bond k resolves its force against (bond_law's joint_normal), null for a
  /// bond that follows the unified law.
  const Vec3* joint_normal(std::size_t k) const
  {
    if (bond_class.empty())
      return nullptr;
    if (bond_class[k] == BondClass::weak_plane && smooth_joint_normal)
      return &*smooth_joint_normal;
    if (bond_class[k] == BondClass::basal && !basal_normal.empty())
      return &basal_normal[k];
    return nullptr;
  }
  /// The failure constants bond k fails by: its class's, or the law's own (no classes).
  const FailureConstants& failure_constants(std::size_t k) const
  {
    if (failure.by_class && !bond_class.empty())
      return failure.classes[std::size_t(bond_class[k])];
    return failure;
  }
  /// Share (1 - D) of its trial forces that bond k carries (0 when broken).
  double load_factor(std::size_t k) const
  {
    if (state[k] == BondState::broken)
      return 0.0;
    return damage.empty() ? 1.0 : 1.0 - damage[k];
  }
  /// Puts the bonds in the order `order` (new k = old order[k]), every per-bond array alike.
  void reorder(const std::vector<std::size_t>& order);
  /// Room for n bonds in every array that add() fills (no growth slack: a million-particle
  /// specimen holds six million bonds).
  void reserve(std::size_t n);
  /// Bytes the store holds (the capacity of every array).
  std::size_t memory_bytes() const;
  /// The constants of bond k as formed (inverse of add's BondStiffness argument).
  BondStiffness stiffness(std::size_t k) const;
  void add(std::int32_t ia, std::int32_t ib, double length, const Vec3& axis, BondModel m,
           const BondStiffness& k);
};
} // namespace dembridge::dem
