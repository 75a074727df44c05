#pragma once
// Stresses in a bonded assembly (thesis section 3.6, after Potyondy and Cundall 2004).
//
// Particle stress (eq. 59-62): the average stress in sphere p is
//     sigma^(p)_ij = (1 / V_p) sum_c (x_c - x_p)_i F_j^(c),
// summed over the particle's bonds that are not broken (a softening bond with its (1 - D) share,
// bond_damage.h), with x_c the bond's contact point and F^(c) the
// contact force ACTING ON p. (The thesis writes a minus sign because its F is the force the
// particle exerts; both conventions give tension positive, compression negative.) External
// loads and support reactions act at particle centres and add nothing; bond couples are
// neglected as in the thesis. The tensor is not symmetric particle by particle; its volume
// average over a region in equilibrium is (the antisymmetric parts cancel with the couples).
//
// RVE average (eq. 54): sigma_ij = (1 / V) sum_{p: centroid in the RVE} V_p sigma^(p)_ij.
//
// Bond forces come from the particle state alone (no recorded forces), so the same code serves
// the explicit and the static solver (see StressTheory).
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include <array>
#include <vector>

namespace dembridge::dem
{
using Tensor3 = Eigen::Matrix3d;

struct ParticleStresses
{
  std::vector<Tensor3> sigma; ///< Pa, per particle
  std::vector<double> volume; ///< m^3, per particle (4/3 pi r^3)
  double strain_energy = 0;   ///< J, elastic energy of the bonds ((1 - D) U_e if softening)
};

/// A bond's contact-point force and couple acting on particle b (global frame).
struct BondContactForce
{
  Vec3 force = Vec3::Zero();  ///< N
  Vec3 moment = Vec3::Zero(); ///< N m
};

/// Bond k's contact force and couple on b in the current state (positions, orientations, and
/// velocities for its dashpots), times the share 1 - D it carries (zero once broken): the
/// unified law of the force loop (bond_kernel.h), evaluated for one bond when it is needed
/// (ParaView bond files), so that a run does not keep 48 bytes a bond of records for it.
BondContactForce bond_contact_force(const ParticleStore& p, const BondStore& bonds, std::size_t k);

/// Stores every unbroken bond's elastic contact force and couple (on b, times 1 - D) of the current
/// configuration in bonds.force / bonds.moment (what the explicit solver records on its
/// recording steps); for states the explicit solver did not produce (static solution).
void record_bond_forces(const ParticleStore& p, BondStore& bonds);

/// Which theory the stresses follow:
///  - small_strain: bond forces of the linearised law (the 12x12 bond matrices of the static
///    solver) from the displacements and rotations, lever arms x_c - x_p in the reference
///    configuration. The linear-elastic stress: exact for the static solver's solution (the
///    RVE average equals the boundary stress and is symmetric to solver tolerance) and what
///    elastic-constant studies compare with the continuum.
///  - current: the unified law's forces in the current configuration with current lever arms
///    (Cauchy-type, for large rotations); differs from small_strain at O(strain).
/// V_p is the sphere volume in both.
enum class StressTheory
{
  small_strain,
  current
};

/// Particle stresses of the current state.
ParticleStresses particle_stresses(const ParticleStore& p, const BondStore& bonds,
                                   StressTheory theory = StressTheory::small_strain);

/// Eq. 54 over the particles whose centroids (reference positions) lie in [lo, hi], divided by
/// the given RVE volume V (m^3).
Tensor3 rve_average(const ParticleStore& p, const ParticleStresses& s, const Vec3& lo,
                    const Vec3& hi, double volume);

/// Sub-volume averages: the box [lo, hi] cut into n slabs of equal thickness along `axis`,
/// particles assigned by reference centroid, each slab's eq. 54 over its own volume.
struct StressLayers
{
  int axis = 2;
  std::vector<double> edges;  ///< n + 1 slab boundaries (m)
  std::vector<Tensor3> sigma; ///< n averages (Pa)
  std::vector<int> count;     ///< particles per slab
};
StressLayers stress_layers(const ParticleStore& p, const ParticleStresses& s, const Vec3& lo,
                           const Vec3& hi, int axis, int n);

/// Histogram of sigma_cc / mean(sigma_cc) over all particles (thesis Fig. 36).
struct StressHistogram
{
  int component = 0;         ///< c: the normal component sigma_cc
  double mean = 0;           ///< Pa
  double std_dev = 0;        ///< Pa
  double max_ratio = 0;      ///< max sigma_cc / mean
  std::vector<double> edges; ///< bin edges of sigma_cc / mean
  std::vector<long> counts;
};
StressHistogram stress_histogram(const ParticleStresses& s, int component, int bins);
} // namespace dembridge::dem
