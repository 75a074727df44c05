#pragma once
// Output of bond failures:
//  - cracks.csv: one row per broken bond: time (s), bond midpoint x y z (m), bond axis x y z,
//    mode (tension | shear: which stress governed), released energy (J: the strain energy of a
//    brittle bond, the energy a softening bond dissipated), particle ids a b and the bond index;
//    with a microstructure (dem/microstructure/) also the bond's class (intra_grain,
//    grain_boundary, weak_plane) and, with grains, whether the crack ran between two grains
//    (intergranular) or through one (transgranular);
//    written under a temporary name and renamed when the run completes;
//  - cracks.pvd + cracks_NNNNNN.vtu: at every snapshot, every crack so far as a point at its bond
//    midpoint (ParaView: Glyph with the `axis` vector): time, energy, axis, particle_a,
//    particle_b and bond (Int64) as point data, mode (UInt8: 0 tension, 1 shear) and with a
//    microstructure class (UInt8, as the bonds' files) as cell data (particle_vtu_file.h);
//  - summary.json: n_broken_bonds, broken_bonds_tension, broken_bonds_shear, first_crack (time,
//    position, mode), the broken-bond fraction per stress-layer slab (damage_layers) and the
//    peak of the load history (peak_stress and strain_at_peak for uniaxial tests, peak_load and
//    the midspan deflection at it for three-point bending), from
//    dem/measurements/failure_measurements.h; with a microstructure bonds_per_class and
//    broken_bonds_per_class, with grains n_grains and broken_bonds_intergranular /
//    broken_bonds_transgranular; crack_orientation: a histogram of the angle between each
//    crack plane's normal (the bond axis) and the load axis (Measurements/modulus axis), and
//    the same against each of x, y, z (from_axis).
// Runs without a failure law write no crack files.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/solvers/explicit_solver.h"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace dembridge::app
{
class CrackOutput
{
public:
  /// Without a failure law (@p failure_law false) no bond breaks: no file is written.
  CrackOutput(std::filesystem::path dir, bool write_vtu, bool failure_law);
  /// Takes the solver's new failures (its crack log only grows); call on every record.
  void update(const dem::ExplicitSolver& s);
  /// Writes cracks_NNNNNN.vtu with every crack so far.
  void snapshot(double time, long step);
  /// Writes cracks.csv and cracks.pvd.
  void finish() const;
  const std::vector<dem::CrackEvent>& cracks() const { return cracks_; }
  /// The cracks_NNNNNN.vtu snapshots so far (time, file name).
  const std::vector<std::pair<double, std::string>>& files() const { return files_; }
  /// Checkpoints: the snapshot list and how much of the solver's crack log was taken (restored
  /// from the solver's restored log, which is why the solver is visited first).
  void visit_state(dem::StateArchive& a, const dem::ExplicitSolver& s);

private:
  /// Reads the class and grains of cracks_[from...] from the solver's stores.
  void classify(const dem::ExplicitSolver& s, std::size_t from);

  std::filesystem::path dir_;
  bool write_vtu_;
  bool failure_law_;
  std::vector<dem::CrackEvent> cracks_;
  // per crack, with a microstructure: the bond's class; with grains: 1 between two grains
  std::vector<std::uint8_t> classes_, intergranular_;
  bool has_classes_ = false, has_grains_ = false;
  std::vector<std::pair<double, std::string>> files_;
};

/// summary.json, with a microstructure: bonds_per_class, broken_bonds_per_class and with grains
/// n_grains, broken_bonds_intergranular / _transgranular (nothing without one).
void add_bond_class_summary(nlohmann::json& j, const dem::ParticleStore& p,
                            const dem::BondStore& b);

/// summary.json: crack counts (add_bond_class_summary included), the broken fraction per slab when
/// `layers` > 0 (the slabs of Measurements/stress layers over the specimen's reference extent), and
/// with a failure law and a load axis (0..2; -1: none) the orientation of the crack planes against
/// it (dem/measurements/crack_orientation.h: crack_orientation, nine bins of 10 degrees).
void add_crack_summary(nlohmann::json& j, const std::vector<dem::CrackEvent>& cracks,
                       const dem::ParticleStore& p, const dem::BondStore& b, int layers,
                       int layer_axis, int load_axis = -1);

/// summary.json: peak_stress (Pa) and strain_at_peak of a uniaxial load history (force in N,
/// end displacement in m) over the cross-section area and gauge length: magnitudes, at the
/// record of the largest |force|; final_to_peak_load says how far past the peak the run went.
/// The peak is that of the recorded history: record often (Output/history interval).
void add_peak_stress(nlohmann::json& j, const std::vector<double>& force,
                     const std::vector<double>& displacement, double area, double gauge_length);

/// summary.json: peak_load (N) and the deflection at it (magnitudes), of a bending load history.
void add_peak_load(nlohmann::json& j, const std::vector<double>& load,
                   const std::vector<double>& deflection);
} // namespace dembridge::app
