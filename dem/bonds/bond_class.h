#pragma once
// Bond classes of a specimen with a microstructure (dem/microstructure/): a bond inside one
// grain, a bond joining two grains, a bond crossing a weak plane, a bond of a grain's interior
// that crosses the grain's basal planes (its axis near the grain's c-axis). A class picks the
// bond's stiffness and strength constants when the bond is formed (each class its own Bonds and
// Damage values); the force loop reads the per-bond constants as it does without classes.
#include <array>
#include <cstdint>
#include <string_view>

namespace dembridge::dem
{
enum class BondClass : std::uint8_t
{
  intra_grain,    ///< both particles in one grain (or no microstructure): the Bonds values
  grain_boundary, ///< the particles in two grains
  weak_plane,     ///< the bond crosses a weak plane (whatever the grains)
  basal, ///< inside one grain, its axis within a cone about the grain's c-axis (microstructure.h)
};

inline constexpr std::size_t bond_class_count = 4;

/// The classes' names in enum order (case files, outputs).
inline constexpr std::array<std::string_view, bond_class_count> bond_class_names = {
    {"intra_grain", "grain_boundary", "weak_plane", "basal"}};

inline std::string_view bond_class_name(BondClass c)
{
  return bond_class_names[std::size_t(c)];
}
} // namespace dembridge::dem
