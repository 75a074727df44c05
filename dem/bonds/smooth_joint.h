#pragma once
// The smooth joint: a bond across a joint plane that resolves its force into the plane's
// normal and the plane itself, not along its own axis (Mas Ivars et al. 2011, Int. J. Rock Mech.
// Min. Sci. 48, 219-244, the smooth-joint model of PFC, eq. 1-6; Scholtes & Donze 2012,
// J. Mech. Phys. Solids 60, 1023-1043, YADE's JCFpm, eq. 6-9). Particles sliding along the plane
// then slide on it, rather than having to ride up and over one another, so the joint's
// stiffness and strength do not depend on how the particles happen to sit across the plane.
// Two sets use it: the weak-plane bonds (N the planes' normal) and the basal bonds of a grain's
// interior (N the grain's c-axis, the basal planes' normal; microstructure.h).
//
// With D the relative displacement of a towards b at the bond's contact point (bond_kernel.h:
// D = delta_n e + delta_s, the unified law's deformation) and n the joint's unit normal, from
// a's side of the plane to b's:
//   D_n = D . n,   D_s = D - D_n n                     normal and shear parts         (1)
//   F_c = k_n D_n n + k_s D_s                           contact force on b               (2)
//   M_c = 0                                             a smooth joint carries no couple (3)
//   U   = (k_n D_n^2 + k_s |D_s|^2) / 2                 strain energy                    (4)
// k_n, k_s the bond's own normal and shear stiffnesses (its class's material). The normal
// follows the particles' rotation, as PFC's does, by the mean of its two rotations:
//   n = (q_a n_0 + q_b n_0) / |q_a n_0 + q_b n_0|,   n_0 = sign(N . e_0) N                (5)
// with N the plane's unit normal and e_0 the bond's axis at formation, so the law is objective
// (a rigid rotation of the pair rotates F_c with it and leaves U unchanged). A bond along its
// own normal (e = n) gives the unified law's force: eq. (2) is then k_n delta_n e + k_s delta_s.
// Failure (bond_damage.h, bond_stress.h with M = 0) reads the same stresses against n:
//   sigma = -F_c . n / A,   tau = |F_c - (F_c . n) n| / A                                (6)
// the joint's tensile strength against sigma and its shear strength against tau (constant, or
// Mohr-Coulomb tau_max = c + sigma_c tan phi with sigma_c the compression across the plane), as
// Mas Ivars et al.'s bonded smooth joint and JCFpm's joint bonds fail.
#include "dem/core/lanes.h"

namespace dembridge::dem
{
/// v' = q v for a unit quaternion q read as (x, y, z, w): v' = v + w u + q_v x u, u = 2 q_v x v.
template <class T> [[gnu::always_inline]] inline void rotate_by(const T* q, const T* v, T* out)
{
  const T x = q[0], y = q[1], z = q[2], w = q[3];
  const T ux = 2 * (y * v[2] - z * v[1]), uy = 2 * (z * v[0] - x * v[2]),
          uz = 2 * (x * v[1] - y * v[0]);
  out[0] = v[0] + w * ux + (y * uz - z * uy);
  out[1] = v[1] + w * uy + (z * ux - x * uz);
  out[2] = v[2] + w * uz + (x * uy - y * ux);
}

/// The joint's current normal, eq. (5), from its formation normal n_0 (already signed).
template <class T>
[[gnu::always_inline]] inline void joint_normal_now(const T* qa, const T* qb, const T* n0, T* n)
{
  T na[3], nb[3];
  rotate_by(qa, n0, na);
  rotate_by(qb, n0, nb);
  const T sx = na[0] + nb[0], sy = na[1] + nb[1], sz = na[2] + nb[2];
  const T inv = 1.0 / lane_sqrt(sx * sx + sy * sy + sz * sz);
  n[0] = sx * inv, n[1] = sy * inv, n[2] = sz * inv;
}

/// The contact force of eq. (2) and the energy of eq. (4) from the deformation D and the
/// current normal n.
template <class T>
[[gnu::always_inline]] inline void smooth_joint_force(const T* D, const T* n, T kn, T ks, T* F,
                                                      T& energy)
{
  const T dn = D[0] * n[0] + D[1] * n[1] + D[2] * n[2]; // eq. (1)
  const T sx = D[0] - dn * n[0], sy = D[1] - dn * n[1], sz = D[2] - dn * n[2];
  const T fn = kn * dn;
  F[0] = fn * n[0] + ks * sx, F[1] = fn * n[1] + ks * sy, F[2] = fn * n[2] + ks * sz; // eq. (2)
  energy = 0.5 * (kn * dn * dn + ks * (sx * sx + sy * sy + sz * sz));                 // eq. (4)
}
} // namespace dembridge::dem
