#pragma once
// An adaptive particle region: the continuum turns into bonded particles, by whole layers of
// cells, where its stress approaches the particle model's strength (docs/adaptive.md).
//
// Cells. The region's grid is one box grid (coupled_mesh.h) whose cells have the band element
// size h inside the *envelope* (the box where the region may grow; the FE domain by default)
// and grow away from it; its lines do not move. The particle region is a set of the envelope's
// cells (a RegionVolume of their union, handshake.h: its band lies along the faces inside the
// domain), at the start the cells of the particle box (Particles/origin, box size).
// FE grid. A subset of the grid's lines: per axis, inside the envelope, the lines within a fine
// zone and every k-th line (k = `envelope coarsening`, from the envelope's lower face)
// elsewhere; outside the envelope all lines (graded as for a fixed region: coarse cells there,
// next to a support, stiffened the test beam by 0.5 %). The fine zone along an axis is empty
// while the region has no face normal to it inside the domain (a beam's width that it spans);
// once it has, the envelope's whole extent (`fine margin` = 0), or the hull of m = `fine
// margin` cells on either side of those faces, widened outward to the coarse lines. It never
// narrows: a growth only adds lines, so the earlier continuum's Q1 field is exactly a field of
// the new grid (a trilinear cell cut along its lines stays trilinear), and region_growth.cc
// interpolates it at the new nodes. Exact, but not in equilibrium on the finer grid (coarse Q1
// cells are stiffer in bending): refined under load, the continuum rings (the 4 m beam: its
// load reading +-27 N about 60 N, the first bond broken 20 ms early), hence the default. With
// m >= n + ceil(R / h) (n the growth's layers, below) a growth from a cell marked at the
// region's face reaches at most n cells past it, and those cells' averages reach R further, so
// the measure that decides the next growth near the region sees fine cells only; m must be at
// least the band's depth in cells (a coarse cell would straddle the band's inner edge). A
// coarse FE cell gives its strain, at the centre of each grid cell it covers, to those cells.
// Utilisation. At each record the continuum's strain eps_c at the centre of each FE cell c gives
// the utilisation U_c = U(eps_c) (packing_strength.h: the packing's bonds deformed with the
// continuum against their strengths); its non-local average over the radius R (Bazant & Jirasek
// 2002, the bell-shaped weight w(r) = (1 - r^2 / R^2)^2, by cell volume V) is
//   Ubar_c = sum_{c'} w(|x_c - x_c'|) V_c' U_c' / sum_{c'} w(|x_c - x_c'|) V_c',
// over the FE cells c' within R (the particle-only region has no continuum and is left out).
// Checks: at every record (coupled_run.h), and while bonds break every `crack check interval`
// steps (a record each): a crack runs about half a spacing a step at most (its speed is below
// the waves', the step below a spacing's crossing time), so that it cannot cross the band
// between two checks.
// Growth. Every FE cell with Ubar_c >= threshold is marked (band cells too: the band is held
// elastic), and every band cell holding a bond whose failure index (coupled_problem.h,
// BandDamage: on the bond's whole force, against its own strength) is at or above the band
// threshold: the particle model's own measure where damage nears the band. (Its scale is not
// Ubar's: a bond's index carries its own strength's scatter and its bending, which the
// continuum's average does not: docs/adaptive.md.)
// The region takes every envelope cell within n whole layers of a marked cell (index distance n
// along each axis), n = ceil(L / h - 1/2) + layers ahead, so that the marked cell's centre ends
// deeper than the band width L and becomes particle-only. The region never shrinks (no switching
// back). Cells that touch a fixed or driven FE node (the supports, the driven faces) never join:
// the continuum keeps its boundary conditions. Refused at a check: a threshold passed in every FE
// cell (a uniform stress: the region would grow through the whole body). Capped: a growth that
// would put more than `maximum particles` in the region is not made (the run says so once and
// goes on with the region it has).
// Packing. The packing a full-DEM run would use: the lattice over the envelope (a lattice
// continued by whole periods: the envelope's lower corner lies a whole number of periods from
// the domain's, and the cells hold whole particles), generated once; the region keeps its
// particles whose centres lie in its cells. Units: m, s.
#include "coupling/coupled_mesh.h"
#include "coupling/handshake.h"
#include "coupling/packing_strength.h"
#include "coupling/region_volume.h"
#include "dem/core/state_archive.h"
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace dembridge::fem
{
class ExplicitDynamics;
}

namespace dembridge::coupling
{
struct AdaptiveRegionSettings
{
  bool enabled = false;
  double threshold = 0.7;            ///< Ubar at which a cell turns into particles, in (0, 1]
  double band_threshold = 0.8;       ///< a band bond's failure index that turns its cell, in (0, 1]
  double averaging_radius = 0;       ///< R, m; 0: the band width
  std::size_t maximum_particles = 0; ///< 0: no cap
  int layers_ahead = 2;              ///< whole layers beyond the least that makes a cell deep
  /// While bonds break, growth is checked every this many steps (each a record) instead of at
  /// every record: a crack can cross the band between two records.
  long crack_check_interval = 10;
  bool envelope_given = false; ///< false: the FE domain
  int envelope_coarsening = 4; ///< k: FE lines every k grid lines away from the region, >= 1
  int fine_margin = 0;         ///< m, grid cells beyond the region's faces; 0: n + ceil(R / h)
  Vec3 envelope_lo = Vec3::Zero(), envelope_hi = Vec3::Zero(); ///< m
};

/// One growth of the region, measured at the state where it happened.
struct GrowthEvent
{
  double time = 0; ///< s
  long step = 0;
  std::size_t cells_added = 0, region_cells = 0;
  std::size_t particles_added = 0, n_particles = 0;
  std::size_t bonds_added = 0, n_bonds = 0;
  std::size_t marked_cells = 0;    ///< FE cells at or above the threshold (either measure)
  std::size_t marked_by_bonds = 0; ///< of them, by a band bond at or above the band threshold
  double max_utilisation = 0;      ///< largest Ubar over the FE cells
  /// Stored energy of both sides (strain, load potential and kinetic energy with the half-step
  /// velocities, J) of the same state before and after the transfer, and the strain energy of
  /// the body before it.
  double energy_before = 0, energy_after = 0, strain_energy = 0;
  double energy_jump() const { return energy_after - energy_before; }
  /// |jump| / the body's strain energy (the goal: <= 1 %).
  double energy_jump_ratio() const
  {
    return strain_energy > 0 ? std::abs(energy_jump()) / strain_energy : 0.0;
  }
  double time_step = 0;    ///< s, the common step after the event
  double wall_seconds = 0; ///< the event's cost
};

class AdaptiveRegion
{
public:
  /// @p lines: the FE box grid (coupled_mesh.h); @p g: the domain and the band width;
  /// @p packing: the packing's centres over the envelope. Throws std::runtime_error naming
  /// Coupling/Adaptive region/<key> on bad input.
  AdaptiveRegion(const AdaptiveRegionSettings& settings, const GridLines& lines,
                 const HandshakeGeometry& g, PackingStrength strength, std::vector<Vec3> packing,
                 double spacing);

  /// The region at the start: the envelope's cells in the box [lo, hi], whose faces must lie on
  /// the grid's lines (throws naming @p key).
  void start_from_box(const Vec3& lo, const Vec3& hi, const std::string& key);
  /// The union of the region's cells (a volume for the handshake).
  std::shared_ptr<const RegionVolume> volume() const;
  bool in_region(const Vec3& x) const { return in_cells(region_, x); }
  /// Whether the grid cell holding @p x is one of @p cells.
  bool in_cells(const std::vector<char>& cells, const Vec3& x) const;
  std::size_t n_region_cells() const;
  std::size_t n_cells() const { return cell_volume_.size(); }
  /// Particles of the packing in the region's cells.
  std::size_t n_region_particles() const { return count_particles(region_); }

  /// U_c and Ubar_c on the continuum's cells from its current displacement (one process);
  /// the cells holding @p marked (the band's bonds at or above the threshold) are marked too.
  void measure(const fem::ExplicitDynamics& fe, const std::vector<Vec3>& marked = {});
  /// Ubar of the grid cell that holds @p x (0 where no continuum is).
  double averaged_utilisation(const Vec3& x) const;
  double max_utilisation() const { return max_utilisation_; }
  /// The largest Ubar of all measures so far.
  double largest_utilisation() const { return largest_utilisation_; }

  struct Proposal
  {
    enum class Kind
    {
      none,      ///< nothing marked, or nothing left to add
      grow,      ///< cells: the region after growing
      capped,    ///< the growth would pass `maximum particles`
      whole_body ///< every FE cell marked: a uniform stress
    } kind = Kind::none;
    std::vector<char> cells;
    std::size_t cells_added = 0, marked = 0, marked_by_bonds = 0, particles = 0;
  };
  /// The growth the last measure() asks for (nothing is changed).
  Proposal propose() const;

  /// Index of the packing's centre at @p x (a reference position), -1 if none.
  std::int32_t packing_index(const Vec3& x) const;
  const std::vector<Vec3>& packing() const { return packing_; }
  const AdaptiveRegionSettings& settings() const { return settings_; }
  const PackingStrength& strength() const { return strength_; }
  /// The packing's bond directions (from the first model's bonds, before blending).
  void set_families(std::vector<BondFamily> families);
  bool has_families() const { return !strength_.families.empty(); }
  /// The region's cells (one char per grid cell: i fastest, then j, then k).
  const std::vector<char>& cells() const { return region_; }
  /// The grid's cell faces per axis (cells() indexes the cells between them).
  const GridLines& lines() const { return lines_; }
  /// The FE grid's lines now (file comment: fine zone and every k-th line).
  GridLines fe_lines() const;
  /// Per axis the fine zone's first and last grid line (first > last: none).
  using Zone = std::array<std::array<int, 3>, 2>;
  const Zone& fine_zone() const { return fine_zone_; }
  /// Widens the fine zone to m cells beyond the region's faces (after the region grew).
  void widen_fine_zone();
  /// The region's grid: the envelope's cells of size @p h, outside it cells graded as
  /// coupled_mesh_steps makes them.
  static GridLines envelope_grid(const HandshakeGeometry& g, const Vec3& envelope_lo,
                                 const Vec3& envelope_hi, const Vec3& element_size, double h,
                                 const Vec3& far_element_size, double growth);
  void set_cells(std::vector<char> cells);
  /// Checkpoints: the region's cells and the last measure (a restored region of other cells is
  /// the caller's to rebuild on).
  void visit_state(dem::StateArchive& a);

private:
  std::size_t cell_index(int i, int j, int k) const
  {
    return (std::size_t(k) * n_[1] + std::size_t(j)) * n_[0] + std::size_t(i);
  }
  /// The grid cell holding x (clamped to the grid).
  std::array<int, 3> cell_of(const Vec3& x) const;
  Vec3 centre(std::size_t c) const;
  std::size_t count_particles(const std::vector<char>& cells) const;
  std::array<std::int64_t, 3> key(const Vec3& x) const;
  /// The constructor's steps (adaptive_region.cc).
  void check_settings();
  double lay_out_cells();
  void require_whole_particles_in_cells() const;
  void index_packing();
  void find_envelope_lines();
  void lay_out_averaging();
  void average_utilisation();
  /// FE values at the centres of the grid cells an FE cell covers, by their counts per axis.
  using CoveredValues = std::map<std::array<int, 3>, std::unique_ptr<dealii::FEValues<3>>>;
  /// U of the grid cells that the FE cell @p cell covers (its strain at their centres).
  void measure_cell(const fem::ExplicitDynamics& fe,
                    const dealii::DoFHandler<3>::active_cell_iterator& cell, CoveredValues& cache);

  AdaptiveRegionSettings settings_;
  GridLines lines_;
  HandshakeGeometry geometry_;
  PackingStrength strength_;
  std::vector<Vec3> packing_;
  double spacing_ = 0;
  std::array<int, 3> n_{{0, 0, 0}};
  std::vector<double> cell_volume_;
  std::vector<char> envelope_;     ///< the cell may join the region
  std::vector<char> region_;       ///< the cell is in the region
  std::vector<char> continuum_;    ///< the cell is an FE cell (at the last measure)
  std::vector<char> anchored_;     ///< the cell touches a fixed or driven FE node
  std::vector<float> utilisation_; ///< U_c
  std::vector<float> averaged_;    ///< Ubar_c
  std::vector<char> bond_marked_;  ///< the cell holds a band bond at or above the threshold
  std::vector<std::uint32_t> cell_particles_;
  std::map<std::array<std::int64_t, 3>, std::int32_t> packing_index_;
  double max_utilisation_ = 0;
  double largest_utilisation_ = 0;
  /// Per axis and grid cell: the first cell of the average's reach, and from offset[i] to
  /// offset[i + 1] the squared centre distances (m^2) to the cells from it on.
  struct AveragingAxis
  {
    std::vector<int> first, offset;
    std::vector<double> distance2;
  };
  std::array<AveragingAxis, 3> averaging_axes_;
  int layers_ = 1; ///< n of the file comment
  int margin_ = 0; ///< m of the file comment
  std::array<int, 3> envelope_first_{{0, 0, 0}}, envelope_last_{{0, 0, 0}}; ///< grid lines
  Zone fine_zone_{{{{1, 1, 1}}, {{0, 0, 0}}}};                              ///< none yet
};
} // namespace dembridge::coupling
