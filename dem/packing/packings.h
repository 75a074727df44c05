#pragma once
// Regular packings and particle files.
//  - row: spheres on a straight line (beams, cantilevers);
//  - simple cubic: spacing 2r, porosity 1 - pi/6;
//  - HCP: layers of triangular lattices in ABAB stacking, spacing 2r, porosity 1 - pi/(3 sqrt 2);
//  - FCC: the same layers in ABC stacking (the same ideal porosity, cubic symmetry);
//  - CSV particle files "x, y, z, r" (SI units; separators comma, semicolon or blanks; '#'
//    starts a comment; the first line that is no comment may be a header naming the columns
//    x, y, z, r (or radius) in any order). Spheres that overlap by more than max_file_overlap
//    of the smaller radius are refused.
#include "dem/core/particle_store.h"
#include "dem/model/case_config.h"
#include <istream>

namespace dembridge::dem
{
/// Fills `p` from the source; throws InputError (naming Particles/...) on bad input. A random
/// packing runs on `threads` threads (the same packing on any count).
void generate_particles(const ParticleSource& src, ParticleStore& p, int threads = 1);

/// Keeps the particles whose centres @p keep accepts (their masses and reference positions).
void keep_particles(ParticleStore& p, const std::function<bool(const Vec3&)>& keep);

/// Largest overlap r_i + r_j - |x_i - x_j| a particle file may hold, relative to the smaller
/// radius (a random packing saved by this code overlaps by at most 1e-4).
inline constexpr double max_file_overlap = 0.01;

/// Reads a CSV particle file; throws InputError naming the file and line.
void read_particle_file(const std::string& path, double density, ParticleStore& p);
/// The same from a stream; @p name stands for the file in messages.
void read_particles(std::istream& in, const std::string& name, double density, ParticleStore& p);
} // namespace dembridge::dem
