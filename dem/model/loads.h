#pragma once
// Supports and loads on particle groups.
//  - Constraint: DOFs of every particle of a group held fixed (velocity zero).
//  - Load: a force or moment (total over the group, shared equally by its particles), or a
//    prescribed velocity, angular velocity or displacement (per particle, on the chosen
//    components).
// Every load follows a ramp from 0 at t = 0 to its full value at t = ramp_time, stays there, and
// is removed at end_time (a prescribed DOF is then released). Forces, moments and velocities
// ramp linearly. A displacement u(t) = value f(t / ramp_time) follows the ramp profile:
//   linear  f(s) = s                  (constant velocity value / ramp_time: strain-rate control)
//   smooth  f(s) = 3 s^2 - 2 s^3      (zero velocity at both ends: no shock, quasi-static)
// and both solvers read it the same way: the static solver as the displacement u(t) (final
// state: value), the explicit solver as the velocity (u(t + dt) - u(t)) / dt over each step, so
// the displacement is exact at every step.
// A pressure is a normal stress on a face group (a confining stress, as servo walls or a
// pressure cell apply it): the group total force at time t is
//   F(t) = (p_0 factor(t) + R sigma_ref) A d
// with d the unit direction it pushes (`value`, into the specimen), A the face's area, p_0 the
// confining pressure and R the ratio to sigma_ref, the stress carried by another (prescribed
// motion) load: its group's support reaction along its own value over its `area`, as measured
// at the previous step. R > 0 holds sigma_2 = p_0 + R sigma_1 through a test whose sigma_1 is
// driven by displacement (Smith & Schulson's proportional biaxial loading; p_0 = 0 for a fixed
// ratio, R = 0 for a fixed confining stress).
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
  angular_velocity,
  displacement,
  pressure
};

enum class RampProfile
{
  linear,
  smooth
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
  RampProfile profile = RampProfile::linear;                 ///< displacement loads
  /// m^2: a pressure's face area; a load another one's ratio refers to: the area its reaction
  /// acts on (sigma_ref = reaction / area)
  double area = 0;
  double pressure = 0; ///< Pa, p_0 of a pressure (ramped as a force)
  double ratio = 0;    ///< R of a pressure
  int ratio_load = -1; ///< index of the load giving sigma_ref; -1: none

  /// Fraction of the full value at time t (0 after end_time).
  double factor(double t) const
  {
    if (t >= end_time)
      return 0.0;
    return ramp_time > 0 && t < ramp_time ? t / ramp_time : 1.0;
  }
  /// Displacement loads: the fraction f(t / ramp_time) of `value` reached at time t (held
  /// after the ramp; an instantaneous step for ramp_time 0).
  double displacement_fraction(double t) const
  {
    if (!(ramp_time > 0) || t >= ramp_time)
      return 1.0;
    const double s = t > 0 ? t / ramp_time : 0.0;
    return profile == RampProfile::smooth ? s * s * (3.0 - 2.0 * s) : s;
  }
  bool active(double t) const { return t < end_time; }
  bool prescribes_motion() const
  {
    return kind == LoadKind::velocity || kind == LoadKind::angular_velocity ||
           kind == LoadKind::displacement;
  }
};
} // namespace dembridge::dem
