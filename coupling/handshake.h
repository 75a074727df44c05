#pragma once
// The handshake (bridging domain) geometry and the blending weights of a coupled run
// (Xiao & Belytschko 2004, Comput. Methods Appl. Mech. Engrg. 193, 1645-1669, sections 2-3).
//
// Regions. The FE domain is a box; the particle region is a box inside it, or the volume of a
// gmsh mesh (region_volume.h). A face of the particle box that lies inside the domain is a
// coupled face (of a volume: the boundary triangles not lying on a face of the domain, the
// coupled surface); the handshake band is the layer of the particle region next to them:
//   s(x) = min over coupled faces of (distance of x inside that face)       (m)
//   s(x) = distance from x to the coupled surface                (a volume, x inside it)
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
// A volume's band need not follow the FE cells: the FE mesh keeps every cell with a quadrature
// point outside the particle-only region (coupled_mesh.h), and the weights are evaluated at the
// quadrature points and bond midpoints as for a box.
// Units: m. The weights are dimensionless.
#include "coupling/region_volume.h"
#include "dem/core/types.h"
#include <array>
#include <memory>
#include <utility>
#include <vector>

namespace dembridge::coupling
{
using dem::Vec3;

struct HandshakeGeometry
{
  Vec3 domain_lo = Vec3::Zero(), domain_hi = Vec3::Zero();     ///< FE domain box, m
  Vec3 particle_lo = Vec3::Zero(), particle_hi = Vec3::Zero(); ///< particle region box, m
  /// The particle region as a gmsh volume (particle_lo/hi become its bounding box); null: the box.
  std::shared_ptr<const RegionVolume> region;
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
  /// Coupled faces of the particle box (of a volume's bounding box): x-, x+, y-, y+, z-, z+.
  const std::array<bool, 6>& coupled_faces() const { return coupled_; }
  /// Triangles of a volume's coupled surface (0 for a box).
  std::size_t n_coupled_triangles() const { return surface_.size(); }

  /// s(x): signed depth below the coupling surface (m); only meaningful inside the region (of a
  /// volume: +infinity beyond 1.5 L from the coupled surface).
  double depth(const Vec3& x) const;
  /// Inside the particle region (the box, or the volume).
  bool in_particle_box(const Vec3& x) const;
  /// Energy weight of the particles alpha(x) in [0, 1].
  double alpha(const Vec3& x) const;
  /// Centre inside the closed band (tied particles), with a tolerance of 1e-9 L.
  bool in_band(const Vec3& x) const;
  bool in_particle_only(const Vec3& x) const;
  /// f + (1 - 2 f) alpha(x) in the band, 1 in the particle-only region, 0 outside; and the FE
  /// density weight w_M(x) = 1 - particle_mass_share(x), except in the particle-only region: f
  /// there, the value at the band's inner edge. Only the FE cells a volume's band cuts reach into
  /// that region (a box's band planes are cell faces); their nodes there carry no stiffness
  /// (1 - alpha = 0) but must keep a mass for the explicit step (the lumped mass is read at the
  /// nodes).
  double particle_mass_share(const Vec3& x) const;
  double fe_mass_weight(const Vec3& x) const;
  double fe_stiffness_weight(const Vec3& x) const { return 1.0 - alpha(x); }

  /// The box of the particle-only region: the particle box shrunk by L on coupled faces.
  std::pair<Vec3, Vec3> particle_only_box() const;
  /// The band's planes s = 0 and s = L per axis where a face is coupled (the FE mesh is aligned
  /// with them); for a volume, its bounding box's planes (the FE mesh has band-sized cells
  /// between them).
  std::array<std::vector<double>, 3> band_planes() const;

private:
  /// depth(x) for an x known to lie in the region (a volume's containment test skipped).
  double depth_inside(const Vec3& x) const;

  HandshakeGeometry g_;
  std::array<bool, 6> coupled_{};
  SurfaceDistance surface_; ///< a volume's coupled surface
};
} // namespace dembridge::coupling
