#pragma once
// Regular packings and particle files.
//  - row: spheres on a straight line (beams, cantilevers);
//  - simple cubic: spacing 2r, porosity 1 - pi/6;
//  - HCP: layers of triangular lattices in ABAB stacking, spacing 2r, porosity 1 - pi/(3 sqrt 2);
//  - FCC: the same layers in ABC stacking (the same ideal porosity, cubic symmetry);
//  - CSV particle files "x, y, z, r" (SI units, '#' comments, optional header line).
#include "dem/model/case_config.h"
#include "dem/core/particle_store.h"

namespace dembridge::dem
{
/// Fills `p` from the source; throws InputError (naming Particles/...) on bad input.
void generate_particles(const ParticleSource& src, ParticleStore& p);

/// Reads a CSV particle file; throws InputError naming the file and line.
void read_particle_file(const std::string& path, double density, ParticleStore& p);
} // namespace dembridge::dem
