#pragma once
// Supports and loads on particle groups.
//  - Constraint: DOFs of every particle of a group held fixed (velocity zero).
//  - Load: a force or moment (total over the group, shared equally by its particles), or a
//    prescribed velocity or angular velocity (per particle, on the chosen components).
// Every load follows a linear ramp from 0 at t = 0 to its full value at t = ramp_time, stays
// there, and is removed at end_time (a prescribed DOF is then released).
#include "dem/core/types.h"
#include <limits>
#include <string>

namespace dembridge::dem
{
struct Constraint
{
  int group = 0;
  std::uint8_t dofs = 0; ///< DofBit mask
};

enum class LoadKind
{
  force,
  moment,
  velocity,
  angular_velocity
};

struct Load
{
  std::string name;
  int group = 0;
  LoadKind kind = LoadKind::force;
  Vec3 value = Vec3::Zero();   ///< N, N·m (group total) or m/s, rad/s (per particle)
  std::uint8_t components = 7; ///< prescribed components (bits x, y, z) for velocities
  double ramp_time = 0.0;      ///< s
  double end_time = std::numeric_limits<double>::infinity(); ///< s

  /// Fraction of the full value at time t (0 after end_time).
  double factor(double t) const
  {
    if (t >= end_time)
      return 0.0;
    return ramp_time > 0 && t < ramp_time ? t / ramp_time : 1.0;
  }
  bool active(double t) const { return t < end_time; }
  bool prescribes_motion() const
  {
    return kind == LoadKind::velocity || kind == LoadKind::angular_velocity;
  }
};
} // namespace dembridge::dem
