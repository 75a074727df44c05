#include "app/runs/fem_run.h"
#include "app/output/fem_history.h"
#include "fem/elastic_problem.h"
#include <deal.II/base/mpi.h>
#include <memory>

namespace dembridge::app
{
namespace fs = std::filesystem;

namespace
{
/// The output folder's files of an FE run, written as the run reaches them.
class FemRunFiles final : public fem::CaseObserver
{
public:
  FemRunFiles(const fem::Parameters& p, const fs::path& dir, MPI_Comm comm)
      : p_(p), dir_(dir), root_(dealii::Utilities::MPI::this_mpi_process(comm) == 0)
  {
  }

  void on_solved(fem::ElasticProblem& problem) override
  {
    if (p_.write_vtu)
      fem::write_fields(problem, dir_, 0, 0.0);
  }

  void on_dynamics_start(fem::ExplicitDynamics& problem, const fem::DynamicsStart& s) override
  {
    // a resumed run writes the snapshots after its checkpoint again
    if (s.resumed && root_)
      fem::remove_later_fe_snapshots(dir_, p_.base_name, problem.snapshot_records());
    history_ = std::make_unique<FemHistory>(dir_ / "history.csv", root_, s.n_probes,
                                            s.resumed ? s.history_length : -1);
    if (p_.write_vtu && s.steps_done == 0)
      fem::write_fields(problem, dir_, 0, 0.0);
  }

  void on_step(fem::ExplicitDynamics& problem, const fem::DynamicsRow& row) override
  {
    history_->add(row);
    const unsigned int n = row.step;
    if (p_.write_vtu && p_.output_every > 0 && (n + 1) % p_.output_every == 0)
      fem::write_fields(problem, dir_, (n + 1) / p_.output_every, problem.time());
  }

  long history_length() override { return long(history_->durable_size()); }

  /// The last rows, and the last step's fields unless a regular snapshot just wrote them.
  void on_dynamics_end(fem::ExplicitDynamics& problem) override
  {
    history_->close();
    if (p_.write_vtu && (p_.output_every == 0 || p_.n_steps % p_.output_every != 0))
      fem::write_fields(problem, dir_, p_.output_every == 0 ? 1 : p_.n_steps / p_.output_every + 1,
                        problem.time());
  }

private:
  const fem::Parameters& p_;
  const fs::path dir_;
  const bool root_;
  std::unique_ptr<FemHistory> history_;
};
} // namespace

nlohmann::json run_fem_case(const fem::Parameters& p, const fs::path& output_dir, MPI_Comm comm,
                            const fem::DynamicsCheckpoints* checkpoints)
{
  FemRunFiles files(p, output_dir, comm);
  const fem::CaseResult result = fem::run_case(p, comm, files, checkpoints);
  write_timing_log(output_dir, result.timing_table,
                   dealii::Utilities::MPI::this_mpi_process(comm) == 0);
  return result.figures;
}
} // namespace dembridge::app
