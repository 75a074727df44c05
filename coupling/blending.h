#pragma once
// Blending the particle side of a coupled run (bridging domain method, Xiao & Belytschko 2004,
// eq. 6-9).
//   bonds     every bond's stiffnesses and dashpots times the energy weight alpha at its
//             reference midpoint (handshake.h). The unified bond law is linear in k_n, k_s,
//             k_tor, k_ben and the dashpot coefficients, so the scaled arrays give alpha times
//             the bond's force, moment and strain energy, and the explicit solver needs no change.
//   masses    a band particle p takes the share of its mass that the FE nodes around it lack:
//               w_p = 1 - sum_I N_I(X_p) M_I^w / M_I,
//             with M_I^w the node's lumped mass with the FE density weight w_M and M_I without
//             it (coupled_build.cc computes it). Where every FE node sits on a particle the two
//             sides' masses then sum to the body's mass node by node; the continuous weights of
//             handshake.h would add or lose a fraction f/2 of a particle layer's mass at the
//             band's two edges, whose reflection (measured: 3.5e-4 of the incident energy for
//             f = 0.1, 3.3e-3 for f = 0.3) this removes. w_p is kept at least f/2.
//   inertia   a particle's rotations are not tied (the continuum has none), so its rotational
//             inertia must not be lighter than its bonds are weak: the weight is
//               w_I = max(w_p, largest alpha of its bonds),
//             which keeps every rotational frequency at or below the full lattice's (the
//             explicit step of the particle region stays valid in the band).
#include "coupling/handshake.h"
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include <vector>

namespace dembridge::coupling
{
struct ParticleBlending
{
  std::vector<int> interface;      ///< particles whose centres lie in the band (tied)
  std::vector<double> mass_weight; ///< w_p per particle
  std::vector<double> inertia_weight;
  /// Bonds whose weight alpha (at the reference midpoint) is below 1: the band's, and alpha.
  std::vector<std::size_t> band_bonds;
  std::vector<double> band_bond_alpha;
};

/// The band particles. Throws std::runtime_error if a particle centre lies outside the particle
/// region or none lies in the band.
std::vector<int> find_interface_particles(const Handshake& h, const dem::ParticleStore& p);

/// Scales masses, inertias, bond stiffnesses and dashpots in place; @p interface_mass_weight
/// holds w_p of the interface particles, the others (particle-only region) keep weight 1.
ParticleBlending blend_particles(const Handshake& h, const std::vector<int>& interface,
                                 const std::vector<double>& interface_mass_weight,
                                 dem::ParticleStore& p, dem::BondStore& b);
} // namespace dembridge::coupling
