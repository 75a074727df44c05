#pragma once
// The explicit solver's orientation update (thesis eq. 45, in quaternion form):
//   q^{n+1} = exp(dt w^{n+1/2} / 2) q^n = (cos a, (sin a / a) h) q^n,   h = dt w^{n+1/2} / 2,
//   a = |h|, with the series cos a ~ 1 - a^2/2 + a^4/24 and sin a / a ~ 1 - a^2/6 + a^4/120
//   below a^2 = 1e-6 (truncation below 1e-19),
// then renormalised: a product of unit quaternions has |q|^2 = 1 + roundoff, which one Newton
// step for 1/|q| from 1, (3 - |q|^2)/2, removes without a square root and a division; a
// quaternion far from unit length (set by hand) is divided by its norm.
// Quaternions in Eigen's storage order (x, y, z, w). Eight consecutive particles at a time in
// SIMD lanes when all eight turn by less than a^2 = 1e-6 (every step of a quasi-static or
// small-strain run): the particle update's scalar quaternion product and its latency were about
// a tenth of a bond-benchmark step. Either path computes the same expressions, so a particle's
// result depends only on its block of eight, not on the thread count.
#include <cmath>

namespace dembridge::dem
{
/// q <- (c, s h) q, renormalised (the expressions above, written out per component).
[[gnu::always_inline]] inline void rotate_quaternion(double* q, double hx, double hy, double hz,
                                                     double c, double s)
{
  const double px = s * hx, py = s * hy, pz = s * hz; // vector part of the rotation quaternion
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  // (c, p) (w, v) = (c w - p . v, c v + w p + p x v)
  const double nw = c * w - (px * x + py * y + pz * z);
  const double nx = c * x + w * px + (py * z - pz * y);
  const double ny = c * y + w * py + (pz * x - px * z);
  const double nz = c * z + w * pz + (px * y - py * x);
  const double n2 = nx * nx + ny * ny + nz * nz + nw * nw;
  const double f = std::abs(n2 - 1.0) < 1e-8 ? 0.5 * (3.0 - n2) : 1.0 / std::sqrt(n2);
  q[0] = nx * f, q[1] = ny * f, q[2] = nz * f, q[3] = nw * f;
}

/// The series factors c ~ cos a, s ~ sin a / a for a^2 < 1e-6.
[[gnu::always_inline]] inline void small_angle_factors(double a2, double& c, double& s)
{
  c = 1.0 - a2 / 2.0 + a2 * a2 / 24.0;
  s = 1.0 - a2 / 6.0 + a2 * a2 / 120.0;
}

/// q turned by h = dt w / 2, a2 = |h|^2: the series below a2 = 1e-6, cos and sin above.
inline void turn_quaternion(double* q, double hx, double hy, double hz, double a2)
{
  double c, s;
  if (a2 < 1e-6)
    small_angle_factors(a2, c, s);
  else
  {
    const double a = std::sqrt(a2);
    c = std::cos(a);
    s = std::sin(a) / a;
  }
  rotate_quaternion(q, hx, hy, hz, c, s);
}

/// One particle: q (4 doubles) turned by the angular velocity w (3 doubles) over dt.
inline void update_orientation(double* q, const double* w, double dt)
{
  const double hx = 0.5 * dt * w[0], hy = 0.5 * dt * w[1], hz = 0.5 * dt * w[2];
  turn_quaternion(q, hx, hy, hz, hx * hx + hy * hy + hz * hz);
}

/// Eight consecutive particles (q: 32 doubles, w: 24): in SIMD lanes if all eight angles are
/// small, else one particle at a time.
inline void update_orientations8(double* q, const double* w, double dt)
{
  double hx[8], hy[8], hz[8], a2[8];
  bool small = true;
  for (int j = 0; j < 8; ++j)
  {
    hx[j] = 0.5 * dt * w[3 * j], hy[j] = 0.5 * dt * w[3 * j + 1], hz[j] = 0.5 * dt * w[3 * j + 2];
    a2[j] = hx[j] * hx[j] + hy[j] * hy[j] + hz[j] * hz[j];
    small = small & (a2[j] < 1e-6);
  }
  if (!small)
  {
    for (int j = 0; j < 8; ++j)
      turn_quaternion(q + 4 * j, hx[j], hy[j], hz[j], a2[j]);
    return;
  }
#pragma GCC ivdep
  for (int j = 0; j < 8; ++j)
  {
    double c, s;
    small_angle_factors(a2[j], c, s);
    rotate_quaternion(q + 4 * j, hx[j], hy[j], hz[j], c, s);
  }
}
} // namespace dembridge::dem
