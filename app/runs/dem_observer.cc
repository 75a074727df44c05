#include "app/runs/dem_observer.h"
#include "app/output/dem_history.h"
#include "app/runs/dem_static_run.h"
#include <algorithm>
#include <cstdio>
#include <deal.II/base/mpi.h>
#include <iomanip>

namespace dembridge::app
{
CaseObserver::CaseObserver(const std::filesystem::path& dir, const OutputSettings& out,
                           const dem::Model& model, const CheckpointSettings& checkpoint,
                           bool failure_law)
    : model_(model), vtu_(dir, group_names(model)), write_vtu_(out.write_vtu), dir_(dir),
      history_path_(dir / "history.csv"), cracks_(dir, out.write_vtu, failure_law),
      checkpoint_(checkpoint)
{
  // Written under a temporary name and renamed when the run completes, so an interrupted
  // run never leaves a history that looks complete.
  // A resume keeps the interrupted run's file; visit_state cuts it back to the checkpoint.
  history_file_.open(dir / "history.csv.part", checkpoint.resume);
  if (!checkpoint.resume)
    history_ << history_header(model, contacts_);
  history_ << std::setprecision(10);
}

LoadHistory CaseObserver::load_history() const
{
  LoadHistory h;
  h.axial_displacement = du_;
  h.axial_loaded_force = force_;
  h.axial_fixed_force = fixed_force_;
  h.flexural_load = flex_load_;
  h.flexural_deflection = flex_u_;
  // the records before the first bond broke: the elastic part
  h.flexural_records_intact = std::size_t(
      std::find_if(flex_broken_.begin(), flex_broken_.end(), [](std::int64_t n) { return n > 0; }) -
      flex_broken_.begin());
  return h;
}

std::pair<double, double> CaseObserver::kinetic_share() const
{
  double largest = 0;
  const double t_end = kinetic_share_.empty() ? 0 : kinetic_share_.back().first;
  for (const auto& [t, share] : kinetic_share_)
    if (t >= 0.5 * t_end)
      largest = std::max(largest, share);
  return {largest, kinetic_share_.empty() ? 0.0 : kinetic_share_.back().second};
}

void CaseObserver::on_record(const dem::ExplicitSolver& s)
{
  if (loaded_ >= 0)
  {
    du_.push_back(s.group_mean_displacement(loaded_)[axis_] -
                  s.group_mean_displacement(fixed_)[axis_]);
    force_.push_back(s.group_force(loaded_)[axis_]);
    fixed_force_.push_back(-s.group_force(fixed_)[axis_]);
  }
  if (top_ >= 0)
  {
    flex_load_.push_back(s.group_force(pin_).z() + s.group_force(roller_).z());
    flex_u_.push_back(
        -0.5 * (s.group_mean_displacement(top_).z() + s.group_mean_displacement(bottom_).z()));
    flex_broken_.push_back(s.n_broken_bonds());
  }
  cracks_.update(s);
  const auto& e = s.energy();
  if (e.kinetic + e.strain > 0)
    kinetic_share_.emplace_back(s.time(), e.kinetic / (e.kinetic + e.strain));
  history_row(
      history_,
      {s.steps(), s.time(), e, s.max_speed(), s.unbalanced_force_ratio(), s.n_broken_bonds()},
      model_.particles, s.groups(), contacts_);
}

void CaseObserver::on_start(dem::ExplicitSolver& s, dem::RunProgress& progress)
{
  if ((checkpoint_.enabled() || checkpoint_.resume) && !s.checkpointable())
    throw dem::InputError("Output/checkpoint interval: this run has forces (a coupling?) "
                          "that cannot be checkpointed yet");
  if (!checkpoint_.resume)
    return;
  read_checkpoint(checkpoint_.file, [&](dem::StateArchive& a) { visit_state(a, s, progress); });
  std::printf("resumed from %s: step %ld, t = %.6g s\n", checkpoint_.file.string().c_str(),
              s.steps(), s.time());
  std::fflush(stdout);
}

void CaseObserver::on_checkpoint(dem::ExplicitSolver& s, dem::RunProgress& progress)
{
  // one writer: a DEM run started on several MPI ranks runs the same model on each
  if (checkpoint_.file.empty() || dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return;
  write_checkpoint(checkpoint_.file, make_checkpoint_header(checkpoint_, s.steps(), s.time()),
                   [&](dem::StateArchive& a) { visit_state(a, s, progress); });
}

void CaseObserver::on_snapshot(const dem::ExplicitSolver& s)
{
  if (write_vtu_)
    vtu_.write(model_.particles, model_.bonds, s.time(), s.steps());
  cracks_.update(s);
  cracks_.snapshot(s.time(), s.steps());
}

void CaseObserver::on_progress(const dem::ExplicitSolver& s, double fraction, double rate,
                               double eta)
{
  std::printf("[%5.1f%%] step %ld, t = %.4g s, %.3g steps/s, %.3g bond-updates/s, ETA %.0f s, "
              "max speed %.3g m/s\n",
              100 * fraction, s.steps(), s.time(), rate, rate * double(model_.bonds.size()), eta,
              s.max_speed());
  std::fflush(stdout);
}

void CaseObserver::finish()
{
  history_file_.close();
  std::filesystem::rename(history_path_.string() + ".part", history_path_);
  if (write_vtu_)
    vtu_.finish();
  cracks_.finish();
}

void CaseObserver::visit_state(dem::StateArchive& a, dem::ExplicitSolver& s,
                               dem::RunProgress& progress)
{
  s.visit_state(a);
  progress.visit_state(a);
  dem::StateGroup group(a, "output");
  a.io("axial_displacement", du_);
  a.io("axial_force", force_);
  a.io("axial_fixed_force", fixed_force_);
  std::vector<double> share_time, share;
  for (const auto& [t, k] : kinetic_share_)
    share_time.push_back(t), share.push_back(k);
  a.io("kinetic_share_time", share_time);
  a.io("kinetic_share", share);
  a.io("flexural_load", flex_load_);
  a.io("flexural_deflection", flex_u_);
  a.io("flexural_broken_bonds", flex_broken_);
  long history_bytes = a.loading() ? 0 : long(history_file_.durable_size());
  a.io("history_bytes", history_bytes);
  vtu_.visit_state(a);
  cracks_.visit_state(a, s);
  if (!a.loading())
    return;
  if (share_time.size() != share.size())
    throw dem::InputError(a.where() + "kinetic_share: not as long as its times");
  if (flex_broken_.size() != flex_load_.size())
    throw dem::InputError(a.where() + "flexural_broken_bonds: not as long as 'flexural_load'");
  kinetic_share_.clear();
  for (std::size_t k = 0; k < share.size(); ++k)
    kinetic_share_.emplace_back(share_time[k], share[k]);
  // history.csv as at the checkpoint, and no snapshot of the interrupted run after it
  history_file_.resume_at(history_bytes);
  remove_later_dem_snapshots(dir_, vtu_, cracks_.files());
}
} // namespace dembridge::app
