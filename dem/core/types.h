#pragma once
// Basic types of the DEM core. SI units throughout: m, kg, s, N, N·m, Pa.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace dembridge::dem
{
using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

/// Thrown for any non-physical or inconsistent input. The message is one line that names
/// the offending parameter (Section/key) or file and the reason.
class InputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Degree-of-freedom bits of one particle: three translations then three rotations.
enum DofBit : std::uint8_t
{
  dof_ux = 1u << 0,
  dof_uy = 1u << 1,
  dof_uz = 1u << 2,
  dof_rx = 1u << 3,
  dof_ry = 1u << 4,
  dof_rz = 1u << 5,
};

/// Parses "ux, uy, rz" (any subset of ux uy uz rx ry rz, or "all"/"none") into a DofBit mask.
std::uint8_t parse_dof_mask(const std::string& text, const std::string& where);
} // namespace dembridge::dem
