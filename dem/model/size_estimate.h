#pragma once
// How big a case will be before it is built: particles, bonds and the memory they take, so that
// a case the machine cannot hold is refused at once with the figures instead of ending in
// std::bad_alloc (or the kernel's OOM killer) after minutes.
//
// Counts: lattices exactly (the layer and row counts of packings.cc, closed form), a random
// packing by the number of spheres the packer draws, (1 - target porosity) V / (4/3 pi E[R^3]),
// a row by its count, a particle file by its lines. Bonds: the coordination of the lattice with
// the contact radius multiplier (counted on a small block of the same lattice), 6.8 m^3 for a
// random packing, the explicit pairs when given.
// Memory: bytes per particle and per bond from the stores' element types (ParticleStore,
// BondStore), doubled for vector growth, plus what the solver and the output add per particle
// and per bond (measured; tests/dem/test_size_estimate.cc keeps the estimate above the heap a
// built model really takes).
#include "dem/core/available_memory.h"
#include "dem/model/case_config.h"
#include <string>

namespace dembridge::dem
{
struct SizeEstimate
{
  double particles = 0; ///< expected number of particles
  double bonds = 0;     ///< expected number of bonds
  double bytes = 0;     ///< peak memory of building, solving and writing the case (B)
  std::string key;      ///< the parameter that sets the size (Particles/radius, ...)
};

/// Bytes one particle / one bond occupies in ParticleStore / BondStore (element sizes only).
double stored_bytes_per_particle();
double stored_bytes_per_bond();
/// Peak bytes per particle and per bond of a run (stores with growth slack, solver, output).
double peak_bytes_per_particle(bool static_solver);
double peak_bytes_per_bond(bool static_solver);

/// Estimates the case's size; reads nothing but the line count of a particle file (relative
/// paths from the working directory). Never throws for a consistent config; a missing file
/// gives zero particles (the build reports it).
SizeEstimate estimate_size(const CaseConfig& config);

/// Throws InputError naming estimate.key, the estimate and @p available when the estimate does
/// not fit (available > 0; see available_memory_bytes()).
void check_fits_in_memory(const SizeEstimate& estimate, double available);
} // namespace dembridge::dem
