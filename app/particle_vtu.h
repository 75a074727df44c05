#pragma once
// ParaView output of a bonded-particle state through deal.II's DataOutBase (no hand-written VTK):
//  - particles: one vertex patch each, with radius, displacement, velocity, angular velocity,
//    force, moment, group mask and coordination;
//  - bonds: one line patch each (particle centre to particle centre), with normal force
//    (tension positive), shear force, twisting moment, bending moment, the force vector, the
//    bond state (0 intact, 1 softening, 2 broken), the tensile and shear stress of beam theory on
//    the bond section (dem/bonds/bond_stress.h, Pa) and the damage D.
// Snapshots go to DIR/particles_NNNNNN.vtu and DIR/bonds_NNNNNN.vtu; the .pvd time series are
// written by finish().
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace dembridge::app
{
class ParticleVtuSeries
{
public:
  explicit ParticleVtuSeries(std::filesystem::path dir) : dir_(std::move(dir)) {}
  void write(const dem::ParticleStore& p, const dem::BondStore& b, double time, long step);
  /// Writes particles.pvd and bonds.pvd listing every snapshot.
  void finish() const;
  /// (time, file name relative to DIR) of every snapshot so far: particles and bonds.
  const std::vector<std::pair<double, std::string>>& particle_files() const
  {
    return particle_files_;
  }
  const std::vector<std::pair<double, std::string>>& bond_files() const { return bond_files_; }

private:
  std::filesystem::path dir_;
  std::vector<std::pair<double, std::string>> particle_files_, bond_files_;
};
} // namespace dembridge::app
