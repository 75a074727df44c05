#pragma once
// The utilisation of a continuum strain against the strength of a bonded packing: the largest
// failure index of the packing's bonds when they deform with the continuum (what an adaptive
// particle region reads, adaptive_region.h).
//
// A bond of rest length L_0 along the unit axis n, in a body under the small strain eps whose
// particles follow the body's displacement and rotation (the affine, Cauchy-Born assumption),
// has at its contact point (bond_kernel.h: approach delta_n, transverse offset delta_s)
//   delta_n = -L_0 (n . eps n),        delta_s = L_0 (eps n - (n . eps n) n),
// and no couple (its neighbours rotate alike), so the unified law's contact force is
// F = k_n delta_n n + k_s delta_s and the bond's stresses (bond_stress.h, Potyondy & Cundall
// 2004 eq. 9-10, with M = 0) are
//   sigma = k_n L_0 (n . eps n) / A,    tau = k_s L_0 |eps n - (n . eps n) n| / A,
// A = pi R_b^2. The utilisation is the largest failure index (bond_damage.h eq. 1-2) over the
// packing's bond directions, against the bonds' mean strengths sigma_t and tau_c (or c):
//   U(eps) = max_n max(sigma / sigma_t, tau / tau_max(sigma)).
// eps is the continuum's strain; its stress is C eps with the packing's own tensor
// (coupled_case.h), so U measures the continuum's stress against the packing's strength.
// Simple cubic lattice (spacing d, parallel bonds of radius R_b, C11 = k_n / d,
// C44 = k_s / (2 d)): a bond along x carries the normal force sigma_xx d^2 and the shear forces
// sigma_xy d^2, sigma_xz d^2 of its cell's face, so this is the lattice's closed-form strength:
// uniaxial tension fails at sigma_xx = sigma_t pi R_b^2 / d^2 (pi sigma_t / 4 for R_b = d / 2),
// pure shear at sigma_xy = tau_c pi R_b^2 / d^2. Exact for the lattice's elastic response
// (an FCC lattice likewise: one particle per periodic cell); an HCP lattice relaxes a little
// off the affine motion (two particles per cell). Not included: the bonds' bending from the
// strain's gradient (curvature kappa adds sigma = E_b R_b kappa for parallel bonds, R_b / (h/2)
// of the bending stress in a beam of depth h: 10 % at h = 10 d) and the strength scatter (a bond
// weaker by the scatter fails at a lower U): the threshold's margin below 1 covers both.
// Units: Pa, m, N/m; U is dimensionless.
#include "dem/bonds/bond_damage.h"
#include "dem/bonds/bond_model.h"
#include "dem/core/types.h"
#include <Eigen/Dense>
#include <vector>

namespace dembridge::coupling
{
using dem::Vec3;

/// The bonds of one direction of a packing: axis (unit, either sign), stiffnesses, rest length
/// and radius.
struct BondFamily
{
  Vec3 axis = Vec3::UnitX();
  double kn = 0, ks = 0;              ///< N/m
  double rest_length = 0, radius = 0; ///< m
};

struct PackingStrength
{
  std::vector<BondFamily> families;
  dem::FailureLaw law;
  double tensile_strength = 0; ///< sigma_t, Pa (mean)
  double shear_strength = 0;   ///< tau_c, or the cohesion c (Mohr-Coulomb), Pa (mean)
};

/// The bond directions of a lattice's bonds (deduplicated up to sign, within 1e-6), each with
/// the unweighted constants of @p material at that bond's length and radii.
std::vector<BondFamily> bond_families(const std::vector<Vec3>& rest_axes,
                                      const std::vector<double>& rest_lengths,
                                      const std::vector<double>& radii_a,
                                      const std::vector<double>& radii_b,
                                      const dem::BondMaterial& material);

/// U(eps) of the file comment; @p strain symmetric.
double utilisation(const PackingStrength& s, const Eigen::Matrix3d& strain);
} // namespace dembridge::coupling
