#pragma once
// A rigid wall: the plane through point(t) with unit normal n (towards the particles). Its
// velocity ramps linearly from 0 at t = 0 to `velocity` at ramp_time and drops to 0 at end_time
// (the velocity loads' ramp, loads.h); the position is the exact integral
//   u(t) = v (t'^2 / (2 T_r))           for t' < T_r
//        = v (T_r / 2 + t' - T_r)       after,           t' = min(max(t, 0), end_time)
// so a wall's displacement over a step is exact and its velocity over the step (u(t + dt) -
// u(t)) / dt is what the particles' leapfrog velocities are compared with.
// A sphere i touches the wall when its gap g = (x_i - point(t)) . n - R_i is negative; the
// overlap is -g. For Hertz the wall is rigid (E -> infinity) and flat (R -> infinity), so
// R* = R_i, m* = m_i, 1/E* = (1 - nu^2)/E, 1/G* = (2 - nu)/G.
#include "dem/contacts/contact_config.h"
#include <algorithm>

namespace dembridge::dem
{
struct Wall
{
  std::string name;
  Vec3 point0 = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ(); ///< unit
  Vec3 velocity = Vec3::Zero();
  double ramp_time = 0, end_time = std::numeric_limits<double>::infinity();

  explicit Wall(const WallConfig& c)
      : name(c.name), point0(c.point), normal(c.normal.normalized()), velocity(c.velocity),
        ramp_time(c.ramp_time), end_time(c.end_time)
  {
  }

  /// Displacement of the plane from t = 0 (m).
  Vec3 displacement(double t) const
  {
    const double s = std::min(std::max(t, 0.0), end_time);
    const double travelled = ramp_time > 0 && s < ramp_time
                                 ? s * s / (2.0 * ramp_time)
                                 : (ramp_time > 0 ? s - 0.5 * ramp_time : s);
    return travelled * velocity;
  }
  Vec3 point(double t) const { return point0 + displacement(t); }
};
} // namespace dembridge::dem
