#pragma once
// ParaView output of a bonded-particle state (particle_vtu_file.h: Float64 points, integer ids,
// cell data, field data):
//  - particles_NNNNNN.vtu: one vertex cell per particle; point data radius, displacement,
//    velocity, angular_velocity, force, moment (vectors), stress (3 x 3 tensor, thesis eq. 62,
//    Pa), group_mask (UInt32: bit g for group g of group_names), coordination (Int32), id (Int64),
//    with a microstructure grain_id (Int32, dem/microstructure/columnar_grains.h);
//  - bonds_NNNNNN.vtu: the particle centres as points (point data particle_id) and one line cell
//    per bond with cell data normal_force (tension positive), shear_force, twisting_moment,
//    bending_moment, force (vector on particle b), state (UInt8: 0 intact, 1 softening,
//    2 broken), tensile_stress and shear_stress (beam theory on the bond section,
//    dem/bonds/bond_stress.h, Pa), damage D and id (Int64, the bond index), with a
//    microstructure class (UInt8: 0 intra_grain, 1 grain_boundary, 2 weak_plane, named in the
//    field data class_names);
//  - both: field data TIME, CYCLE (the step) and group_names (string array).
// The .pvd time series are written by finish() (particle_vtu_file.h: write_pvd, no date).
// A DEM run on several MPI ranks writes both in pieces (ParticlePieces): each rank its own
// particles as particles_NNNNNN_rR.vtu (the same point data, ids included, in id order) and the
// bonds it books as bonds_NNNNNN_rR.vtu (the same cell data, in the order of the bond ids, the
// model's index; its points the bonds' ends, with their particle_id), rank 0 the records
// particles_NNNNNN.pvtu and bonds_NNNNNN.pvtu over them, which particles.pvd and bonds.pvd
// list.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/core/state_archive.h"
#include <deal.II/base/mpi.h>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace dembridge::app
{
class VtuFile; // particle_vtu_file.h
class ParticleVtuSeries
{
public:
  explicit ParticleVtuSeries(std::filesystem::path dir, std::vector<std::string> group_names = {})
      : dir_(std::move(dir)), group_names_(std::move(group_names))
  {
  }
  void write(const dem::ParticleStore& p, const dem::BondStore& b, double time, long step);
  /// From now on write() lists the snapshot's particles and bonds as the .pvtu records that
  /// ParticlePieces writes (just before) and writes nothing.
  void in_pieces() { pieces_ = true; }
  /// Writes particles.pvd and bonds.pvd listing every snapshot.
  void finish() const;
  /// (time, file name relative to DIR) of every snapshot so far: particles and bonds.
  const std::vector<std::pair<double, std::string>>& particle_files() const
  {
    return particle_files_;
  }
  const std::vector<std::pair<double, std::string>>& bond_files() const { return bond_files_; }
  /// Checkpoints: the snapshot lists (the files stay in the staging folder).
  void visit_state(dem::StateArchive& a);

private:
  std::filesystem::path dir_;
  std::vector<std::string> group_names_;
  std::vector<std::pair<double, std::string>> particle_files_, bond_files_;
  bool pieces_ = false;
};

/// The snapshots of a run on several MPI ranks: every rank writes its own particles as a piece
/// particles_NNNNNN_rR.vtu of the snapshot that rank 0's series lists next, and its bonds as
/// bonds_NNNNNN_rR.vtu; rank 0 also the records particles_NNNNNN.pvtu and bonds_NNNNNN.pvtu
/// (rank 0's series then lists them: write()).
class ParticlePieces
{
public:
  /// @p series: rank 0's (it numbers the snapshots and lists the records); null on the others.
  ParticlePieces(std::filesystem::path dir, std::vector<std::string> group_names, MPI_Comm comm,
                 ParticleVtuSeries* series);
  /// Collective: the piece of the first @p n_owned particles of the rank's store (@p b: the
  /// bonds of those particles, for their stress); a failed write throws on every rank.
  void write(const dem::ParticleStore& p, std::size_t n_owned, const dem::BondStore& b, double time,
             long step);
  /// Collective: the piece of the bonds the rank books, @p bonds between the points @p ends (in
  /// the order of their ids: ends.position and ends.id are the points and their particle_id;
  /// the bonds' forces read the ends' orientations and velocities too), @p ids the bonds' ids
  /// (the model's index); @p classes: the model's bonds have classes (a piece without bonds
  /// names the array all the same). A failed write throws on every rank.
  void write_bonds(const dem::ParticleStore& ends, const dem::BondStore& bonds,
                   const std::vector<std::int64_t>& ids, bool classes, double time, long step);

private:
  /// Collective: @p file as this rank's piece of snapshot KIND_NNNNNN (the next one of rank 0's
  /// series), rank 0 also its record.
  void write_piece(const VtuFile& file, const char* kind, double time, long step);

  std::filesystem::path dir_;
  std::vector<std::string> group_names_;
  MPI_Comm comm_;
  ParticleVtuSeries* series_;
};

/// Removes the particle, bond and crack snapshots (particles_, bonds_, cracks_*.vtu, the
/// particles' and bonds' .pvtu records and their pieces) in @p dir
/// that a run interrupted after its last checkpoint wrote: those not in the restored series of
/// @p vtu and @p crack_files (they are written again). Warns of listed ones that are missing.
void remove_later_dem_snapshots(const std::filesystem::path& dir, const ParticleVtuSeries& vtu,
                                const std::vector<std::pair<double, std::string>>& crack_files);

} // namespace dembridge::app
