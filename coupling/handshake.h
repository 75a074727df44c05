#pragma once
// The handshake (bridging domain) geometry and the blending weights of a coupled run
// (Xiao & Belytschko 2004, Comput. Methods Appl. Mech. Engrg. 193, 1645-1669, sections 2-3).
//
// Regions. The FE domain is a box; the particle region is a box inside it. A face of the
// particle box that lies inside the domain is a coupled face; the handshake band is the layer of
// the particle region next to its coupled faces:
//   s(x) = min over coupled faces of (distance of x inside that face)       (m)
//   FE-only region       outside the particle box
//   handshake band       0 <= s <= L          (L: band width)
//   particle-only region s > L
// The band starts at the particle box's face, half a particle spacing outside the outermost
// particle centres of a lattice, so that the bonds a lattice particle lacks there are exactly
// those whose weight would be zero: with alpha linear, the weights of the bonds of every
// particle then sum to 2 alpha(X_p) along each axis, and the forces and moments a uniform strain
// puts on a band particle cancel as in the full lattice (measured: the band planes through the
// outermost centres instead leave those particles an unbalanced moment r F_s d / (2 L) in shear,
// and 1.25 % of a uniform strain's error in the particle-only region).
// Energy weight of the particles (linear ramp, paper eq. 6):
//   alpha(x) = clamp(s / L, 0, 1)  in the particle box,   0 outside it.
// Stiffness: bond forces times alpha at the bond midpoint, FE stress times 1 - alpha at the
// quadrature points; the two sum to one everywhere, which is what a patch test needs.
// Mass: with a floor f (0 < f < 1/2) so that neither side's mass vanishes in the band (an
// explicit step would collapse there). The FE density weight is
//   w_M(x) = 1 - f - (1 - 2 f) alpha(x)   in the band,   1 in the FE-only region,
// from 1 - f at the FE-only edge to f at the particle-only edge; the particles take the rest of
// the mass node by node (blending.h), about w_p = f + (1 - 2 f) alpha (particle_mass_share).
// (MercuryDPM's volume coupling uses weights no lower than about 0.1 for the same reason.)
// Units: m. The weights are dimensionless.
#include "dem/core/types.h"
#include <array>
#include <utility>
#include <vector>

namespace dembridge::coupling
{
using dem::Vec3;

struct HandshakeGeometry
{
  Vec3 domain_lo = Vec3::Zero(), domain_hi = Vec3::Zero();     ///< FE domain box, m
  Vec3 particle_lo = Vec3::Zero(), particle_hi = Vec3::Zero(); ///< particle region box, m
  double band_width = 0;      ///< L, m (at least two particle diameters)
  double weight_floor = 0.1;  ///< f: smallest mass weight of either side in the band
  double particle_radius = 0; ///< r, m (the band must be at least two diameters wide)
};

class Handshake
{
public:
  /// Checks the geometry; throws std::runtime_error naming Coupling/<key> and the reason.
  explicit Handshake(const HandshakeGeometry& g);

  const HandshakeGeometry& geometry() const { return g_; }
  /// Coupled faces of the particle box: x-, x+, y-, y+, z-, z+.
  const std::array<bool, 6>& coupled_faces() const { return coupled_; }

  /// s(x): signed depth below the coupling surface (m); only meaningful inside the box.
  double depth(const Vec3& x) const;
  bool in_particle_box(const Vec3& x) const;
  /// Energy weight of the particles alpha(x) in [0, 1].
  double alpha(const Vec3& x) const;
  /// Centre inside the closed band (tied particles), with a tolerance of 1e-9 L.
  bool in_band(const Vec3& x) const;
  bool in_particle_only(const Vec3& x) const;
  /// f + (1 - 2 f) alpha(x) in the band, 1 in the particle-only region, 0 outside; and the FE
  /// density weight w_M(x) = 1 - particle_mass_share(x).
  double particle_mass_share(const Vec3& x) const;
  double fe_mass_weight(const Vec3& x) const { return 1.0 - particle_mass_share(x); }
  double fe_stiffness_weight(const Vec3& x) const { return 1.0 - alpha(x); }

  /// The box of the particle-only region: the particle box shrunk by L on coupled faces.
  std::pair<Vec3, Vec3> particle_only_box() const;
  /// The band's planes s = 0 and s = L per axis where a face is coupled (the FE mesh is aligned
  /// with them).
  std::array<std::vector<double>, 3> band_planes() const;

private:
  HandshakeGeometry g_;
  std::array<bool, 6> coupled_{};
};
} // namespace dembridge::coupling
