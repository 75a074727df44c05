#pragma once
// Bond formation. A bond joins two particles whose contact radii touch or overlap:
//   |x_a - x_b| <= eta_r (R_a + R_b)           (paper Fig. 4; eta_r = contact radius multiplier)
// with a relative tolerance of 1e-9 so that lattice neighbours exactly in contact are bonded.
// Formation also resets orientations to identity: rotations are measured from this moment.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"

namespace dembridge::dem
{
/// Makes the current state the reference: orientations identity (bond rotations are measured
/// from here) and reference positions = positions (displacements are measured from here).
void mark_reference_configuration(ParticleStore& p);

/// Bonds every pair within contact range and marks the reference configuration; returns the
/// number of bonds added.
std::size_t form_bonds(ParticleStore& p, BondStore& bonds, const BondMaterial& mat,
                       double contact_radius_multiplier);

/// Adds one bond between particles i and j (explicit bond lists).
void add_bond(ParticleStore& p, BondStore& bonds, const BondMaterial& mat, int i, int j);

/// Sets the dashpot coefficients of every bond (thesis eq. 36-37, paper eq. 9-10):
///   c_t = xi 2 sqrt(k_n m_red) / sqrt(C/3),  c_r = xi 2 sqrt(2 k_tor I_red) / sqrt(C/3)
/// with m_red = m_a m_b/(m_a+m_b), I_red likewise and C the mean coordination of the pair.
void assign_bond_damping(const ParticleStore& p, BondStore& bonds, double damping_ratio);
} // namespace dembridge::dem
