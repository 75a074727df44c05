#pragma once
// What an explicit DEM run (Mode = dem) writes and gathers while it runs: history.csv (one row
// per record), the ParaView snapshots, the crack files, console progress, checkpoints, and the
// load histories its modulus figures are fitted to (dem_figures.h).
#include "app/checkpoint/checkpoint.h"
#include "app/input/dem_parameters.h"
#include "app/output/contact_output.h"
#include "app/output/crack_output.h"
#include "app/output/dem_figures.h"
#include "app/output/particle_vtu.h"
#include "dem/core/history_file.h"
#include "dem/model/model.h"
#include "dem/solvers/run_explicit.h"
#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

namespace dembridge::app
{
class CaseObserver : public dem::RunObserver
{
public:
  CaseObserver(const std::filesystem::path& dir, const OutputSettings& out, const dem::Model& model,
               const CheckpointSettings& checkpoint, bool failure_law);

  /// Records the loaded end's axial reaction against the end groups' relative displacement
  /// (the force-displacement curve of thesis eq. 64).
  void track_axial(int fixed, int loaded, int axis)
  {
    fixed_ = fixed, loaded_ = loaded, axis_ = axis;
  }
  /// Records the load a three-point bending specimen carries (the supports' vertical
  /// reactions) against the midspan deflection: the mean downward displacement of the loaded
  /// and the bottom groups (thesis eq. 69's delta, as flexural_response's).
  void track_flexural(int pin, int roller, int loaded, int bottom)
  {
    pin_ = pin, roller_ = roller, top_ = loaded, bottom_ = bottom;
  }
  /// The axial and flexural histories recorded so far.
  LoadHistory load_history() const;
  const CrackOutput& cracks() const { return cracks_; }
  /// The ParaView series of the particles and bonds; null when none is written.
  ParticleVtuSeries* particle_snapshots() { return write_vtu_ ? &vtu_ : nullptr; }
  /// Largest kinetic share KE / (KE + strain energy) over the second half of the run, and the
  /// last one: how quasi-static the loading was.
  std::pair<double, double> kinetic_share() const;

  void on_record(const dem::ExplicitSolver& s) override;
  void on_start(dem::ExplicitSolver& s, dem::RunProgress& progress) override;
  void on_checkpoint(dem::ExplicitSolver& s, dem::RunProgress& progress) override;
  void on_snapshot(const dem::ExplicitSolver& s) override;
  void on_progress(const dem::ExplicitSolver& s, double fraction, double rate, double eta) override;

  /// Renames history.csv into place and closes the ParaView and crack series.
  void finish();

private:
  /// The complete state of the run for a checkpoint: the solver's, the driver's and what this
  /// observer has gathered (load histories, history.csv so far, snapshot and crack lists).
  void visit_state(dem::StateArchive& a, dem::ExplicitSolver& s, dem::RunProgress& progress);

  const dem::Model& model_;
  ContactOutput contacts_{model_}; ///< contact and wall columns of history.csv
  ParticleVtuSeries vtu_;
  bool write_vtu_;
  std::filesystem::path dir_;
  std::filesystem::path history_path_;
  dem::HistoryFile history_file_;
  std::ostream& history_ = history_file_.stream();
  int fixed_ = -1, loaded_ = -1, axis_ = 0;
  std::vector<double> du_, force_, fixed_force_;
  std::vector<std::pair<double, double>> kinetic_share_;
  int pin_ = -1, roller_ = -1, top_ = -1, bottom_ = -1;
  std::vector<double> flex_load_, flex_u_;
  std::vector<std::int64_t> flex_broken_; ///< broken bonds at each flexural record
  CrackOutput cracks_;
  CheckpointSettings checkpoint_;
};
} // namespace dembridge::app
