#pragma once
// What a specimen that breaks is measured by:
//  - damage_layers: the fraction of bonds broken in each slab of the specimen (the slabs of the
//    stress layers, thesis eq. 54), bonds assigned by their midpoint in the reference
//    configuration, and how localised the failure is: the largest share of all broken bonds that
//    two adjacent slabs hold (1 when every broken bond lies in one band two slabs wide);
//  - peak_of: the peak of a load history (largest |load|) and the displacement it came at; the
//    uniaxial tests turn it into peak_stress = F / A and strain_at_peak = du / L (thesis eq. 64's
//    force and gauge length), three-point bending reports the peak load itself;
//  - limit_of: the peak before an unstable crack's load drop (dynamic ringing excluded).
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include <vector>

namespace dembridge::dem
{
struct DamageLayers
{
  int axis = 0;
  std::vector<double> edges;           ///< n + 1 slab boundaries, m
  std::vector<long> bonds, broken;     ///< bonds and broken bonds per slab
  std::vector<double> broken_fraction; ///< broken / bonds per slab (0 for a slab without bonds)
  double localisation = 0; ///< largest share of the broken bonds in two adjacent slabs (0: none)
  int band = -1;           ///< first slab of that pair (-1: nothing broken)
};

/// Slabs [lo, hi] along `axis` cut into n equal layers; a bond belongs to the slab of its
/// reference midpoint (clamped into the end slabs).
DamageLayers damage_layers(const ParticleStore& p, const BondStore& b, const Vec3& lo,
                           const Vec3& hi, int axis, int n);

struct PeakLoad
{
  double load = 0;         ///< value of the largest |load|, with its sign
  double displacement = 0; ///< the displacement at that record
  long index = -1;         ///< record index (-1: empty history)
};

/// The record of the largest |load| (the first one if it repeats); histories of equal length.
PeakLoad peak_of(const std::vector<double>& load, const std::vector<double>& displacement);

/// The limit point: the largest |load| before |load| first falls below half of its running
/// maximum. Where a crack runs unstably (a structure that stores more elastic energy at its peak
/// than the ligament dissipates snaps under displacement control) an explicit run rings
/// afterwards and the overall peak is an inertial spike; the limit point is the peak a
/// quasi-static test measures. Without such a drop it is peak_of's record.
PeakLoad limit_of(const std::vector<double>& load, const std::vector<double>& displacement);

/// Number of leading records before |load| first reaches `fraction` of its peak: the elastic
/// part of the curve of a specimen that breaks (E is fitted there).
std::size_t records_before(const std::vector<double>& load, double fraction);
} // namespace dembridge::dem
