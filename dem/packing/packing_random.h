#pragma once
// Random close packing (RCP) of spheres in a walled box, made by our own dynamic algorithm:
// radius expansion with overlap relaxation ("grow and relax", in the spirit of the
// Lubachevsky-Stillinger and Labra-Onate radius-expansion schemes the thesis cites, section 4.1,
// and of the soft-sphere jamming protocol of O'Hern et al., PRE 68 011306, 2003):
//  1. draw the radii R_i from the distribution until the sphere volume reaches
//     (1 - target porosity) of the box; place the centres uniformly at random with the radii
//     scaled down to s R_i (s = initial_radius_fraction), overlaps allowed;
//  2. repeat: one FIRE step (Bitzek et al., PRL 97 170201, 2006) on the harmonic overlap
//     energy 1/2 sum delta_ij^2, walls as hard constraints (projection), then grow s at a rate
//     that falls to zero as the mean overlap per contact approaches `growth_overlap`; stop at
//     s = 1 (target porosity reached) or when s stalls (jammed, over-compressed);
//  3. relax at fixed s; whenever the overlaps stop falling (jammed) shrink s by half the mean
//     overlap, until the largest overlap is below `overlap_tolerance`: the packing ends at
//     its jamming point, every sphere just touching its neighbours;
//  4. if that happened at s < 1 the target porosity is below what the box admits: restart from
//     the same initial placement with randomly chosen spheres left out, as many as the jammed
//     volume fraction asks for, and repeat 2-3 without the cap at s = 1, so that the packing
//     jams again at s ~ 1 (within 0.2 % for ~3000 spheres; up to two passes, the closest kept).
//     With predict_jamming the first pass is already such a pass, its removal from the
//     predicted jamming porosity (predicted_jamming_porosity; none for a target up to 0.005
//     looser than it, where the capped pass would jam short of s = 1 too), and the measured
//     passes follow only if it jams more than 0.2 % away from s = 1; for a target looser than
//     the prediction they first keep every sphere (removal would only move the jam further
//     past s = 1). A pass that removes nothing is never run twice (it would repeat itself).
// The radii are the drawn ones times the final s (RandomPackingReport::radius_scale). On the
// thesis specimen (0.25 x 0.1 x 0.1 m, r = 5 mm) this gives 2874 spheres and porosity
// 0.397-0.399 for seeds 1-3 (thesis Table 2: 2855-2903 and 0.39-0.40). Seeded: the
// same seed gives bitwise the same packing from the same binary, on any number of threads.
#include "dem/core/particle_store.h"
#include <string>

namespace dembridge::dem
{
struct RandomPackingSettings
{
  Vec3 box_size = Vec3(0.25, 0.1, 0.1); ///< m, the container [0, box]^3 (walls on all faces)
  double mean_radius = 0.005;           ///< m
  enum class Distribution
  {
    mono,    ///< all radii equal the mean (radius_spread ignored)
    uniform, ///< uniform in mean (1 -+ spread)
    normal   ///< normal, std dev spread * mean, truncated to mean (1 -+ 2 spread)
  } distribution = Distribution::mono;
  double radius_spread = 0;      ///< uniform: half-width / mean, in [0, 1); normal: in [0, 0.5)
  unsigned seed = 1;             ///< std::mt19937 seed
  double target_porosity = 0.37; ///< stop growing when reached (or when jammed)

  // Algorithm parameters (defaults tuned on the thesis specimen; see packing_random.cc).
  double initial_radius_fraction = 0.7; ///< s at insertion (porosity ~ 1 - 0.34 (1 - target))
  double growth_rate = 2e-4;            ///< largest relative growth of s per iteration
  double growth_overlap = 2e-2;         ///< mean overlap / mean radius where growth stops
  double overlap_tolerance = 1e-4;      ///< final max overlap / min(R_i, R_j)
  int compaction_cycles = 0;            ///< extra compress-decompress cycles after jamming
  double contact_tolerance = 0.02;      ///< coordination counts |x_i - x_j| <= (1 + tol)(R_i + R_j)
  long max_iterations = 400000;         ///< safety stop (throws if exceeded)
  /// The overlap forces eight pairs at a time where the CPU has AVX-512 (false: one pair at a
  /// time). Either gives bitwise the same packing; the switch is there to test that.
  bool vector_path = true;
  /// Step 4 above with the jamming porosity predicted from the box (predicted_jamming_porosity)
  /// instead of measured by a first pass capped at s = 1: usually one pass instead of three,
  /// with the same porosity and coordination (another packing of the same statistics). False:
  /// the measured estimate (the speed benchmarks use it, so that their recorded packings
  /// stay the same).
  bool predict_jamming = true;
  /// Threads for the overlap forces, the FIRE update and the Verlet list rebuilds (OpenMP).
  /// Every sum keeps its one-thread order, so any count gives bitwise the same packing.
  int threads = 1;
};

struct RandomPackingReport
{
  double porosity = 0;                  ///< 1 - sum of sphere volumes / box volume
  double mean_coordination_contact = 0; ///< 2 pairs / N, pairs counted with contact_tolerance
  long iterations = 0;                  ///< relaxation iterations in all
  double max_overlap_ratio = 0;         ///< max (R_i + R_j - |x_i - x_j|) / min(R_i, R_j), >= 0
  double seconds = 0;                   ///< wall time
  std::size_t particles = 0;            ///< spheres in the packing
  std::size_t removed = 0;              ///< spheres taken out after jamming
  double radius_scale = 1;              ///< final radii / drawn radii (< 1 only if jammed)
};

/// The porosity at which equal spheres jam in the box by this protocol: the bulk value raised
/// near the walls in proportion to the wall area times the radius over the volume,
///   p_J = 0.3605 + 0.156 r A / V,
/// fit to the protocol's own packings of the thesis specimen (r = 5, 2.5, 1.575, 1 mm: 0.398,
/// 0.379, 0.372, 0.368; bench/RESULTS_STATIC.md), within 0.001 of each.
double predicted_jamming_porosity(const RandomPackingSettings& s);

/// Appends a random close packing of the box [0, box_size] to `out` (density in kg/m^3).
/// Throws InputError naming Particles/<key> on bad settings.
RandomPackingReport generate_random_packing(const RandomPackingSettings& settings, double density,
                                            ParticleStore& out);

/// Writes the particles as CSV "x, y, z, r" (m, 17 significant digits, '#' header comment), the
/// format read_particle_file reads. Throws InputError naming the file on failure.
void write_particle_file(const std::string& path, const ParticleStore& p);
} // namespace dembridge::dem
