#include "distributed/run_explicit.h"
#include "dem/contacts/contact_forces.h"
#include "dem/solvers/run_stop.h"
#include "distributed/distributed_particles.h"
#include "distributed/distributed_solver.h"
#include <chrono>
#include <cmath>
#include <csignal>
#include <tuple>
#include <type_traits>

namespace dembridge::distributed
{
std::string unsupported_on_ranks(const dem::Model& model)
{
  for (const auto& c : model.contributions)
  {
    const auto* contacts = dynamic_cast<const dem::ContactForces*>(c.get());
    if (!contacts)
      return "Mode: this run's particle forces do not run on several MPI ranks (run on one rank)";
    if (contacts->monitor().enabled)
      return "Contacts/monitor: the first contact's record does not run on several MPI ranks "
             "(run it on one rank)";
  }
  if (std::string joints = smooth_joints_on_ranks(model.bonds); !joints.empty())
    return joints;
  if (model.groups.size() > 32)
    return "Groups/names: a run on several MPI ranks takes at most 32 groups";
  return {};
}

namespace
{
/// Collective: the state into rank 0's report solver, rank 0's observer writes it; a failed
/// write throws its error on every rank.
void write_checkpoint(DistributedSolver& solver, dem::RunObserver* observer,
                      dem::RunProgress& progress, MPI_Comm comm)
{
  solver.gather_for_checkpoint();
  std::string failed;
  if (solver.report() && observer)
    try
    {
      observer->on_checkpoint(*solver.report(), progress);
    }
    catch (const std::exception& e)
    {
      failed = *e.what() ? e.what() : "checkpoint: unknown error";
    }
  failed = dealii::Utilities::MPI::broadcast(comm, failed, 0);
  if (!failed.empty())
    throw std::runtime_error(failed);
}

/// The largest energy term so far and the worst balance error relative to it.
void track_energy(dem::RunProgress& progress, const dem::EnergyBalance& e)
{
  progress.largest_seen = std::max(progress.largest_seen, e.largest());
  if (progress.largest_seen > 0)
    progress.worst_error = std::max(progress.worst_error, e.error() / progress.largest_seen);
}

/// A record step (collective): the energy tracked, rank 0's report solver filled (the figures,
/// the groups' particles and the crack log; every particle and bond at a snapshot that is not
/// written in pieces: the files read them), the ranks' snapshot pieces written, rank 0's
/// observer called. Returns whether everything was gathered.
bool record_step(DistributedSolver& solver, dem::RunObserver* observer,
                 const SnapshotPieces& pieces, const dem::RunSchedule& sched,
                 dem::RunProgress& progress, long n, bool stop, bool root)
{
  track_energy(progress, solver.energy());
  const bool report = n % sched.record_interval == 0 || n == 1 || stop;
  const bool snapshot =
      n == 1 || stop || (sched.snapshot_interval > 0 && n % sched.snapshot_interval == 0);
  const bool gather_all = snapshot && !pieces;
  if (report || snapshot)
    solver.gather(gather_all);
  if (snapshot && pieces)
  {
    solver.share_ghost_references();
    const DistributedParticles& own = solver.particles();
    pieces(own.particles(), own.n_owned(), own.bonds(), bond_piece(own), solver.time(),
           solver.steps());
  }
  if (root && observer && report)
    observer->on_record(*solver.report());
  if (root && observer && snapshot)
    observer->on_snapshot(*solver.report());
  return gather_all;
}

/// Whether a checkpoint is due after the step that reached @p time (as on one rank,
/// dem::run_explicit): the simulated interval, advanced past the step, or the wall interval by
/// rank 0's clock (@p wall_due, broadcast: collective when a wall interval is set).
bool checkpoint_due(const dem::RunSchedule& sched, dem::RunProgress& progress, double time,
                    double time_step, bool wall_due, MPI_Comm comm)
{
  bool due = false;
  if (sched.checkpoint_interval > 0 && time + 0.5 * time_step >= progress.next_checkpoint_time)
  {
    due = true;
    while (progress.next_checkpoint_time <= time + 0.5 * time_step)
      progress.next_checkpoint_time += sched.checkpoint_interval;
  }
  if (sched.checkpoint_wall_interval > 0)
  {
    int wall = wall_due;
    MPI_Bcast(&wall, 1, MPI_INT, 0, comm);
    due = due || wall;
  }
  return due;
}

/// The run's figures at its end (collective): the energy accumulators as they stand (as one
/// rank's solver().energy() at the end), the final state on rank 0 for the summary (gathered
/// unless the last record did), the deflection group's mean displacement.
void finish_result(dem::RunResult& res, DistributedSolver& solver, const dem::RunProgress& progress,
                   long first_step, bool gathered_all, int deflection_group,
                   const dem::Vec3& direction)
{
  solver.reduce();
  if (!gathered_all)
    solver.gather(true);
  res.steps = solver.steps();
  res.steps_made = solver.steps() - first_step;
  res.time = solver.time();
  res.energy = solver.energy();
  res.energy_balance_error = progress.worst_error;
  res.unbalanced_force_ratio = solver.unbalanced_force_ratio();
  if (deflection_group >= 0)
  {
    res.deflection_vector = solver.group_mean_displacement(deflection_group);
    res.deflection = res.deflection_vector.dot(direction);
  }
}
} // namespace

dem::RunResult run_explicit(dem::Model& model, const dem::CaseConfig& c, dem::RunObserver* observer,
                            dem::RunSchedule sched, MPI_Comm comm, const Resume& resume,
                            const SnapshotPieces& pieces, RanksReport* ranks)
{
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  // why: every rank must take the same steps for records, snapshots and reductions
  static_assert(std::is_trivially_copyable_v<dem::RunSchedule>);
  MPI_Bcast(&sched, int(sizeof(sched)), MPI_BYTE, 0, comm);
  if (const std::string why = unsupported_on_ranks(model); !why.empty())
    throw dem::InputError(why);
  dem::RunProgress progress;
  progress.next_checkpoint_time = sched.checkpoint_interval;
  // rank 0's observer starts (and restores a resumed run) before the particles are spread
  auto restore = [&](dem::ExplicitSolver& whole)
  {
    if (root && observer)
      observer->on_start(whole, progress);
    else if (resume.read)
      resume.read(
          [&](dem::StateArchive& a)
          {
            whole.visit_state(a);
            progress.visit_state(a);
          });
  };
  DistributedSolver solver(
      model, {model.time_step, c.run.particle_damping, c.run.threads, c.run.mass_damping}, comm,
      nullptr, restore, resume.resume, resume.one_rank_contacts);
  const long first_step = solver.steps();
  if (!root) // each rank keeps its part; rank 0 keeps the whole model for the outputs
    model.particles = {}, model.bonds = {};
  dem::RunResult res;
  const int deflection_group =
      c.measure.deflection_group.empty()
          ? -1
          : model.group_index(c.measure.deflection_group, "Measurements/deflection group");
  const int frequency_group =
      c.measure.frequency_group.empty()
          ? -1
          : model.group_index(c.measure.frequency_group, "Measurements/frequency group");
  const dem::Vec3 dir = c.measure.deflection_direction.normalized();
  double loads_end = 0;
  for (const auto& l : model.loads)
    if (std::isfinite(l.end_time))
      loads_end = std::max(loads_end, l.end_time);
  std::vector<double>& ft = progress.frequency_time;
  std::vector<double>& fu = progress.frequency_displacement;
  const long expected = long(std::min(double(c.run.max_steps), c.run.end_time / model.time_step));
  if (frequency_group >= 0)
  {
    ft.reserve(std::size_t(std::max(0L, expected)) + 2);
    fu.reserve(ft.capacity());
  }
  auto last_progress = start, last_checkpoint = start;
  res.stop_reason = "end time";
  bool gathered_all = false;
  while (true)
  {
    const long n = solver.steps() + 1;
    const bool at_end_time = solver.time() + 0.5 * model.time_step >= c.run.end_time;
    const bool record = dem::records_step(n, at_end_time, c.run, sched.record_interval);
    solver.step(record);
    if (frequency_group >= 0 && solver.time() >= loads_end)
    {
      ft.push_back(solver.time());
      fu.push_back(solver.group_mean_displacement(frequency_group).dot(dir));
    }
    const char* reason = dem::stop_reason(solver, c.run, at_end_time, record, loads_end);
    const bool stop = reason != nullptr;
    if (stop)
      res.stop_reason = reason;
    gathered_all = record && record_step(solver, observer, pieces, sched, progress, n, stop, root);
    const auto now = clock::now();
    if (root && observer &&
        std::chrono::duration<double>(now - last_progress).count() > sched.progress_seconds)
    {
      last_progress = now;
      const double wall = std::chrono::duration<double>(now - start).count();
      const double rate = double(solver.steps() - first_step) / wall;
      const double frac = std::min(1.0, solver.time() / c.run.end_time);
      observer->on_progress(*solver.report(), frac, rate,
                            rate > 0 ? (expected - solver.steps()) / rate : 0);
    }
    if (stop)
      break;
    const bool wall_due = root && std::chrono::duration<double>(now - last_checkpoint).count() >=
                                      sched.checkpoint_wall_interval;
    if (checkpoint_due(sched, progress, solver.time(), model.time_step, wall_due, comm))
    {
      write_checkpoint(solver, observer, progress, comm);
      last_checkpoint = clock::now();
    }
    if (sched.kill_after_step > 0 && solver.steps() == sched.kill_after_step)
      std::raise(SIGKILL); // tests of checkpoint and restart (RunSchedule)
  }
  finish_result(res, solver, progress, first_step, gathered_all, deflection_group, dir);
  if (frequency_group >= 0)
    res.natural_frequency = dem::oscillation_frequency(ft, fu);
  if (ranks)
  {
    const DistributedParticles& own = solver.particles();
    ranks->n_repartitions = own.n_repartitions();
    std::tie(ranks->imbalance_max_before, ranks->imbalance_max_after) = own.repartition_imbalance();
  }
  res.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  return res;
}
} // namespace dembridge::distributed
