#pragma once
// Elastic-perfectly plastic history springs of a contact: the tangential spring of Coulomb
// friction (thesis eq. 13: |F_t| <= mu |F_n|, slip beyond) and the rolling spring (Ai et al.
// 2011, model C: |M_r| <= mu_r R* F_n). Each keeps a vector s (tangential displacement, m, or
// rolling angle, rad) in the contact plane; the force (moment) is -k s.
//
// Every step, before the increment, s is carried into the current contact plane (normal n): the
// component along n is removed, the length restored, and s is turned about n by the pair's mean
// spin (Luding 2008, "Cohesive, frictional powders"; LAMMPS pair granular). A pair that turns
// rigidly therefore keeps its spring, and no force grows from the rotation alone.
//
// Stiffness that follows the overlap (Hertz-Mindlin: k_t = 8 G* sqrt(R* delta); the rolling
// spring from k_n) is handled as Mindlin & Deresiewicz describe and Thornton, Cummins & Cleary
// (2011, Powder Technology 210:189-197) implement it: when the overlap grows, the new rim of the
// contact area enters unstressed, so the spring force already carried stays (s scaled by
// k_old/k_new); when it shrinks, the force falls with the stiffness (s kept) by micro-slip in the
// receding rim. Either way the stored energy 1/2 k |s|^2 can only drop; the drop is micro-slip
// dissipation, booked with friction. (Keeping s and letting the force follow k_t on loading too,
// as EDEM does, creates energy: 1-3 % of an oblique impact's energy in our tests.)
//
// Slip: the trial spring s + ds is scaled back to |k s| = cap. The energy the slip dissipates is
// the work of the spring force over the step by the trapezoid rule (the rule the leapfrog
// kinetic energy follows) less the change of the stored energy 1/2 k |s|^2:
//   W_slip = 1/2 k (s_old + s_new) . ds - 1/2 k (|s_new|^2 - |s_old|^2)
//          = 1/2 k (s_old + s_new) . (s_old + ds - s_new)                     (0 when sticking)
#include "dem/core/types.h"
#include <cmath>

namespace dembridge::dem
{
/// Carries a spring vector into the plane normal to the unit vector n, keeping its length, and
/// turns it by the small angle `twist` (rad) about n.
inline Vec3 carry_into_plane(const Vec3& s, const Vec3& n, double twist)
{
  const double length2 = s.squaredNorm();
  if (length2 == 0.0)
    return s;
  Vec3 t = s - s.dot(n) * n;
  t += twist * n.cross(t);
  const double t2 = t.squaredNorm();
  return t2 > 0.0 ? Vec3(t * std::sqrt(length2 / t2)) : Vec3(Vec3::Zero());
}

/// Carries the spring s from stiffness k_old (0: a new contact) to k; returns the stored energy
/// the change dissipates (>= 0).
inline double follow_stiffness(Vec3& s, double k_old, double k)
{
  if (!(k_old > 0) || k == k_old)
    return 0.0;
  const double s2 = s.squaredNorm();
  if (k > k_old) // loading: the force stays
  {
    const double ratio = k_old / k;
    s *= ratio;
    return 0.5 * k_old * s2 * (1.0 - ratio);
  }
  return 0.5 * (k_old - k) * s2; // unloading: the force falls with k
}

/// Adds the increment ds to the spring s of stiffness k and caps |k s| at cap (>= 0). Returns
/// the energy dissipated by slip over the step (J), 0 when the spring sticks.
inline double plastic_spring_step(Vec3& s, const Vec3& ds, double k, double cap)
{
  const Vec3 old = s;
  s += ds;
  const double force = k * s.norm();
  if (force <= cap)
    return 0.0;
  const Vec3 trial = s;
  s *= force > 0 ? cap / force : 0.0;
  return 0.5 * k * (old + s).dot(trial - s);
}
} // namespace dembridge::dem
