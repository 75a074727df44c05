#include "distributed/distributed_solver.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace dembridge::distributed
{
namespace
{
using dem::Vec3;

std::uint64_t pair_key(std::int64_t a, std::int64_t b)
{
  return (std::uint64_t(a) << 32) | std::uint64_t(b);
}

// the figures each rank adds at a record (reduce)
namespace figure
{
enum : std::size_t
{
  kinetic,
  strain,
  damping,
  external,
  initial,
  fracture,
  contact_strain,
  friction,
  contact_damping,
  wall_work,
  max_speed,
  free_force,
  n_free,
  intact_force,
  n_intact,
  n_cracks,
  broken_tension,
  broken_shear,
  count
};
}

constexpr long motion_check_interval = 8;    // steps
constexpr std::size_t particle_doubles = 22; // gather: id, x, v, w, q, F, M, coordination, DOFs
constexpr std::size_t crack_doubles = 11;    // time, a, b, midpoint, axis, mode, energy
constexpr std::size_t bond_state_doubles = 8;
} // namespace

DistributedSolver::DistributedSolver(dem::Model& model, const dem::SolverSettings& settings,
                                     MPI_Comm comm, const BackgroundGrid* grid,
                                     const Restore& restore, bool resume, bool one_rank_contacts)
    : model_(model), comm_(comm), root_(dealii::Utilities::MPI::this_mpi_process(comm) == 0),
      n_ranks_(dealii::Utilities::MPI::n_mpi_processes(comm)), settings_(settings),
      report_(root_ || resume ? std::make_unique<dem::ExplicitSolver>(
                                    model.particles, model.bonds, model.groups, model.constraints,
                                    model.loads, settings)
                              : nullptr),
      particles_(model, restore_whole(grid, restore, resume, one_rank_contacts), comm)
{
  for (const auto& g : model.groups)
    group_sizes_.push_back(g.members.size());
  for (const auto& l : model.loads)
    if (l.kind == dem::LoadKind::pressure && l.ratio_load >= 0 &&
        std::find(followed_loads_.begin(), followed_loads_.end(), l.ratio_load) ==
            followed_loads_.end())
      followed_loads_.push_back(l.ratio_load);
  followed_reactions_.assign(followed_loads_.size(), std::numeric_limits<double>::quiet_NaN());
  followed_buffer_.resize(followed_loads_.size() * n_ranks_);
  if (report_contacts_)
  {
    contacts_ = std::make_unique<dem::ContactForces>(*report_contacts_);
    contacts_->fix_skin(model.particles); // the whole model's, on every rank
    contact_figures_.resize(report_contacts_->n_figures());
    contact_figures_all_.resize(contact_figures_.size() * n_ranks_);
    if (resumed_)
    {
      contact_history_ = std::move(contact_checkpoint_->history());
      if (!root_) // rank 0 continues the sums of the checkpoint
        zero_contact_sums(*contacts_);
    }
  }
  reduce_buffer_.resize(figure::count * n_ranks_);
  if (root_)
  {
    const auto& b = model.bonds;
    bond_index_.reserve(b.has_failure() ? b.size() : 0);
    if (b.has_failure()) // cracks name their bonds by the model's index (the report's order)
      for (std::size_t k = 0; k < b.size(); ++k)
        bond_index_.emplace(pair_key(b.a[k], b.b[k]), k);
    global_of_user_.assign(model.particles.size(), -1);
    for (std::size_t i = 0; i < model.particles.size(); ++i)
      global_of_user_[std::size_t(model.particles.id[i])] = std::int64_t(i);
  }
  if (resumed_)
    continue_restored_run();
  else
    build_local_solver({});
  if (!root_)
    report_.reset(), contact_checkpoint_.reset();
}

BackgroundGrid DistributedSolver::restore_whole(const BackgroundGrid* grid, const Restore& restore,
                                                bool resume, bool one_rank_contacts)
{
  for (const auto& c : model_.contributions)
    if (auto* found = dynamic_cast<dem::ContactForces*>(c.get()))
      report_contacts_ = found;
  if (report_ && report_contacts_)
  {
    contact_checkpoint_ =
        std::make_unique<ContactCheckpoint>(*report_contacts_, resume && one_rank_contacts);
    report_->add_contribution(contact_checkpoint_.get());
    if (resume && one_rank_contacts) // read as that run's contacts were: over the whole model
      report_contacts_->attach(model_.particles, model_.bonds);
  }
  resumed_ = resume;
  // every rank learns whether one could not restore (a damaged checkpoint, say): all stop with
  // the first such rank's error, none waits in the setup's collective calls
  std::string failed;
  try
  {
    if (restore && (root_ || resume))
      restore(*report_);
  }
  catch (const std::exception& e)
  {
    failed = *e.what() ? e.what() : "checkpoint: unknown error";
  }
  const unsigned rank = dealii::Utilities::MPI::this_mpi_process(comm_);
  const unsigned first = dealii::Utilities::MPI::min(failed.empty() ? n_ranks_ : rank, comm_);
  if (first < n_ranks_)
    throw std::runtime_error(dealii::Utilities::MPI::broadcast(comm_, failed, first));
  // why: a resumed run's particles lie where the checkpoint left them
  return grid ? *grid : background_grid_for(model_);
}

void DistributedSolver::continue_restored_run()
{
  auto state = report_->take_running_state();
  report_->set_running_state(dem::ExplicitSolver::RunningState(state));
  energy_ = state.energy, max_speed_ = state.max_speed, unbalanced_ = state.unbalanced;
  unbalanced_ratio_ = state.unbalanced_ratio, broken_by_mode_ = state.broken_by_mode;
  n_broken_ = long(state.cracks.size());
  if (!root_) // the sums and the crack log run on on rank 0; the others start theirs at zero
    state.energy = {}, state.damping_work = 0, state.cracks.clear(), state.broken_by_mode = {},
    state.unbalanced = {};
  cracks_gathered_ = state.cracks.size(); // rank 0's report holds them
  build_local_solver(std::move(state));
  const auto& ids = particles_.global_ids();
  for (std::size_t i = 0; i < particles_.n_owned(); ++i)
    local_->set_support_reaction(i, report_->support_reaction(std::size_t(ids[i])));
  share_group_reactions(); // the restored reactions' sums, which the next step's pressure reads
}

void DistributedSolver::share_group_reactions()
{
  if (followed_loads_.empty())
    return;
  std::vector<double> mine(followed_loads_.size());
  for (std::size_t f = 0; f < mine.size(); ++f)
    mine[f] = local_->own_group_reaction(followed_loads_[f]);
  MPI_Allgather(mine.data(), int(mine.size()), MPI_DOUBLE, followed_buffer_.data(),
                int(mine.size()), MPI_DOUBLE, comm_);
  for (std::size_t f = 0; f < mine.size(); ++f)
  {
    double sum = 0; // in rank order, as the energies
    for (unsigned r = 0; r < n_ranks_; ++r)
      sum += followed_buffer_[r * mine.size() + f];
    followed_reactions_[f] = sum;
    local_->set_group_reaction(followed_loads_[f], sum);
  }
}

void DistributedSolver::build_local_solver(dem::ExplicitSolver::RunningState&& state)
{
  dem::ParticleStore& p = particles_.particles();
  const std::size_t owned = particles_.n_owned();
  std::vector<dem::Group> groups(model_.groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g)
  {
    groups[g].name = model_.groups[g].name;
    for (std::size_t i = 0; i < owned; ++i)
      if (p.group_mask[i] & (1u << g))
        groups[g].members.push_back(int(i));
  }
  // a force or moment on a group is shared by its members: the rank's share is its members'
  std::vector<dem::Load> loads = model_.loads;
  for (auto& l : loads)
    if (!l.prescribes_motion() && group_sizes_[std::size_t(l.group)] > 0)
      l.value *= double(groups[std::size_t(l.group)].members.size()) /
                 double(group_sizes_[std::size_t(l.group)]);
  dem::SolverSettings settings = settings_;
  settings.owned_particles = owned;
  local_ = std::make_unique<dem::ExplicitSolver>(p, particles_.bonds(), std::move(groups),
                                                 model_.constraints, std::move(loads), settings);
  local_->set_running_state(std::move(state));
  for (const auto& [i, r] : particles_.reactions())
    local_->set_support_reaction(i, r);
  for (std::size_t f = 0; f < followed_loads_.size(); ++f)
    if (!std::isnan(followed_reactions_[f])) // (a migration: the sums of the step before it)
      local_->set_group_reaction(followed_loads_[f], followed_reactions_[f]);
  if (contacts_)
  {
    contacts_->distribute(owned, particles_.global_ids(), contact_history_);
    local_->add_contribution(contacts_.get());
  }
}

void DistributedSolver::migrate()
{
  Reactions reactions; // the constrained particles' (ExplicitSolver::support_reaction)
  for (std::size_t i = 0; i < particles_.n_owned(); ++i)
    if (const Reaction r = local_->support_reaction(i); r != Reaction{})
      reactions.emplace_back(std::uint32_t(i), r);
  auto state = local_->take_running_state();
  local_.reset();
  contact_history_.clear();
  if (contacts_)
    contacts_->export_history(contact_history_);
  particles_.rebuild(reactions, contact_history_, dem::ContactForces::history_record_size);
  build_local_solver(std::move(state));
}

void DistributedSolver::step(bool record)
{
  using clock = std::chrono::steady_clock;
  auto since = [](clock::time_point t)
  { return std::chrono::duration<double>(clock::now() - t).count(); };
  record = record || local_->steps() == 0; // the first step records (ExplicitSolver::step)
  auto t0 = clock::now();
  const double step_time = local_->time();
  local_->step(record);
  share_group_reactions();
  timings_.local_step += since(t0);
  t0 = clock::now();
  particles_.update_ghosts();
  timings_.ghosts += since(t0);
  last_step_time_ = step_time;
  // the platens' peak is looked for at every step, as on one rank (else at records: reduce)
  if (contacts_ && contacts_->platens().enabled)
    reduce_contacts(step_time);
  // The motion check is a reduction over the ranks: every few steps. A particle rebuilds at
  // half a cell of travel and is lost only after a whole cell; the other half takes far more
  // steps than this in any run whose time step resolves its bonds and contacts.
  if (steps() % motion_check_interval != 0 && !record)
    return;
  t0 = clock::now();
  const auto& e = local_->energy();
  const auto check =
      particles_.check_motion(!std::isfinite(e.damping) || !std::isfinite(e.external));
  timings_.motion_checks += since(t0);
  if (check.unstable)
    throw std::runtime_error("the simulation became unstable at step " + std::to_string(steps()) +
                             " (t = " + std::to_string(time()) + " s): non-finite energy");
  t0 = clock::now();
  if (check.rebuild)
    migrate();
  timings_.rebuilds += since(t0);
  t0 = clock::now();
  if (record)
    reduce();
  timings_.records += since(t0);
}

void DistributedSolver::reduce()
{
  const dem::EnergyBalance& e = local_->energy();
  const auto parts = local_->unbalanced_parts();
  double mine[figure::count];
  mine[figure::kinetic] = e.kinetic, mine[figure::strain] = e.strain,
  mine[figure::damping] = e.damping;
  mine[figure::external] = e.external, mine[figure::initial] = e.initial,
  mine[figure::fracture] = e.fracture;
  mine[figure::contact_strain] = e.contact_strain, mine[figure::friction] = e.friction;
  mine[figure::contact_damping] = e.contact_damping, mine[figure::wall_work] = e.wall_work;
  mine[figure::max_speed] = local_->max_speed();
  mine[figure::free_force] = parts.free_force, mine[figure::n_free] = double(parts.n_free);
  mine[figure::intact_force] = parts.intact_force, mine[figure::n_intact] = double(parts.n_intact);
  mine[figure::n_cracks] = double(local_->n_broken_bonds());
  mine[figure::broken_tension] = double(local_->broken_bonds(dem::CrackMode::tension));
  mine[figure::broken_shear] = double(local_->broken_bonds(dem::CrackMode::shear));
  MPI_Allgather(mine, int(figure::count), MPI_DOUBLE, reduce_buffer_.data(), int(figure::count),
                MPI_DOUBLE, comm_);
  // sums in rank order: the same on every rank, and from run to run
  double sum[figure::count] = {};
  for (unsigned r = 0; r < n_ranks_; ++r)
    for (std::size_t f = 0; f < figure::count; ++f)
      sum[f] = f == figure::max_speed ? std::max(sum[f], reduce_buffer_[r * figure::count + f])
                                      : sum[f] + reduce_buffer_[r * figure::count + f];
  energy_.kinetic = sum[figure::kinetic], energy_.strain = sum[figure::strain],
  energy_.damping = sum[figure::damping];
  energy_.external = sum[figure::external], energy_.initial = sum[figure::initial];
  energy_.fracture = sum[figure::fracture], energy_.contact_strain = sum[figure::contact_strain];
  energy_.friction = sum[figure::friction], energy_.contact_damping = sum[figure::contact_damping];
  energy_.wall_work = sum[figure::wall_work];
  max_speed_ = sum[figure::max_speed];
  unbalanced_ = {sum[figure::free_force], long(sum[figure::n_free]), sum[figure::intact_force],
                 long(sum[figure::n_intact])};
  // as ExplicitSolver::step forms it from one rank's parts
  const double mean =
      unbalanced_.n_free > 0 ? unbalanced_.free_force / double(unbalanced_.n_free) : 0.0;
  unbalanced_ratio_ = unbalanced_.intact_force > 0
                          ? mean * double(unbalanced_.n_intact) / unbalanced_.intact_force
                          : std::numeric_limits<double>::infinity();
  n_broken_ = long(sum[figure::n_cracks]);
  broken_by_mode_ = {{long(sum[figure::broken_tension]), long(sum[figure::broken_shear])}};
  if (contacts_ && !contacts_->platens().enabled)
    reduce_contacts(last_step_time_);
}

void DistributedSolver::reduce_contacts(double time)
{
  contacts_->figures(contact_figures_.data());
  const int n = int(contact_figures_.size());
  MPI_Gather(contact_figures_.data(), n, MPI_DOUBLE, contact_figures_all_.data(), n, MPI_DOUBLE, 0,
             comm_);
  if (!root_)
    return;
  // sums in rank order, as the energies
  std::fill(contact_figures_.begin(), contact_figures_.end(), 0.0);
  for (unsigned r = 0; r < n_ranks_; ++r)
    for (std::size_t f = 0; f < contact_figures_.size(); ++f)
      contact_figures_[f] += contact_figures_all_[r * contact_figures_.size() + f];
  report_contacts_->set_figures(contact_figures_.data(), time);
}

Vec3 DistributedSolver::group_mean_displacement(int group)
{
  const dem::ParticleStore& p = particles_.particles();
  double mine[3] = {0, 0, 0};
  for (std::size_t i = 0; i < particles_.n_owned(); ++i)
    if (p.group_mask[i] & (1u << group))
      for (int d = 0; d < 3; ++d)
        mine[d] += p.position[i][d] - p.reference_position[i][d];
  std::vector<double> all(3 * n_ranks_);
  MPI_Allgather(mine, 3, MPI_DOUBLE, all.data(), 3, MPI_DOUBLE, comm_);
  Vec3 sum = Vec3::Zero();
  for (unsigned r = 0; r < n_ranks_; ++r)
    sum += Vec3(all[3 * r], all[3 * r + 1], all[3 * r + 2]);
  const auto n = group_sizes_.at(std::size_t(group));
  return n > 0 ? Vec3(sum / double(n)) : sum;
}

void DistributedSolver::gather_bond_states(bool every_bond)
{
  // each bond from the rank of its end a (that books it)
  const dem::BondStore& b = particles_.bonds();
  const auto& ids = particles_.global_ids();
  std::vector<double> mine;
  for (std::size_t k = 0; k < b.size(); ++k)
    if (std::size_t(b.a[k]) < particles_.n_owned() &&
        (every_bond || b.state[k] != dem::BondState::intact))
      mine.insert(mine.end(), {double(ids[std::size_t(b.a[k])]), double(ids[std::size_t(b.b[k])]),
                               double(b.state[k]), b.damage[k], b.kappa_max[k], b.kappa_ultimate[k],
                               b.dissipated[k], double(b.failure_mode[k])});
  const std::vector<double> gathered = gather_on_root(mine, comm_);
  dem::BondStore& whole_bonds = model_.bonds;
  for (std::size_t at = 0; at < gathered.size(); at += bond_state_doubles)
  {
    const double* r = &gathered[at];
    const std::size_t k = bond_index_.at(pair_key(std::int64_t(r[0]), std::int64_t(r[1])));
    whole_bonds.state[k] = dem::BondState(int(r[2]));
    whole_bonds.damage[k] = r[3], whole_bonds.kappa_max[k] = r[4];
    whole_bonds.kappa_ultimate[k] = r[5], whole_bonds.dissipated[k] = r[6];
    whole_bonds.failure_mode[k] = dem::CrackMode(int(r[7]));
  }
}

void DistributedSolver::gather_for_checkpoint()
{
  reduce(); // the sums as they stand (one rank's checkpoint holds its solver's as they stand)
  gather(true);
  if (particles_.bonds().has_failure())
    gather_bond_states(true); // softening history of bonds still intact, and all the rest
  // the support reactions of the last step and the dashpots' work booked half a step ahead
  std::vector<double> mine;
  const auto& ids = particles_.global_ids();
  for (std::size_t i = 0; i < particles_.n_owned(); ++i)
    if (const Reaction r = local_->support_reaction(i); r != Reaction{})
    {
      mine.push_back(double(ids[i]));
      mine.insert(mine.end(), r.begin(), r.end());
    }
  const std::vector<double> reactions = gather_on_root(mine, comm_);
  auto running = local_->take_running_state();
  const std::vector<double> damping_work = gather_on_root({running.damping_work}, comm_);
  local_->set_running_state(std::move(running));
  std::vector<double> history;
  if (contacts_)
  {
    contacts_->export_history(history);
    history = gather_contact_history(history, comm_);
    sum_contact_state(*contacts_, report_contacts_, comm_);
  }
  if (!root_)
    return;
  for (std::size_t i = 0; i < model_.particles.size(); ++i)
    report_->set_support_reaction(i, Reaction{});
  for (std::size_t at = 0; at < reactions.size(); at += 7)
    report_->set_support_reaction(std::size_t(reactions[at]),
                                  {{reactions[at + 1], reactions[at + 2], reactions[at + 3],
                                    reactions[at + 4], reactions[at + 5], reactions[at + 6]}});
  auto state = report_->take_running_state();
  state.damping_work = 0;
  for (const double w : damping_work) // in rank order, as the energies
    state.damping_work += w;
  report_->set_running_state(std::move(state));
  if (contact_checkpoint_)
    contact_checkpoint_->history() = std::move(history);
}

void DistributedSolver::gather(bool all)
{
  const dem::ParticleStore& p = particles_.particles();
  const auto& ids = particles_.global_ids();
  // the particles
  std::vector<double> mine;
  for (std::size_t i = 0; i < particles_.n_owned(); ++i)
  {
    if (!all && p.group_mask[i] == 0)
      continue;
    mine.push_back(double(ids[i]));
    for (const Vec3* v : {&p.position[i], &p.velocity[i], &p.angular_velocity[i]})
      mine.insert(mine.end(), v->data(), v->data() + 3);
    mine.insert(mine.end(), p.orientation[i].coeffs().data(), p.orientation[i].coeffs().data() + 4);
    for (const Vec3* v : {&p.force[i], &p.torque[i]})
      mine.insert(mine.end(), v->data(), v->data() + 3);
    mine.push_back(double(p.coordination[i]));
    mine.push_back(double(p.dof_mask[i])); // which DOFs were prescribed (the measurements)
  }
  std::vector<double> gathered = gather_on_root(mine, comm_);
  dem::ParticleStore& whole = model_.particles;
  for (std::size_t at = 0; at < gathered.size(); at += particle_doubles)
  {
    const double* r = &gathered[at];
    const auto i = std::size_t(r[0]);
    whole.position[i] = Vec3(r[1], r[2], r[3]);
    whole.velocity[i] = Vec3(r[4], r[5], r[6]);
    whole.angular_velocity[i] = Vec3(r[7], r[8], r[9]);
    std::copy(r + 10, r + 14, whole.orientation[i].coeffs().data());
    whole.force[i] = Vec3(r[14], r[15], r[16]);
    whole.torque[i] = Vec3(r[17], r[18], r[19]);
    whole.coordination[i] = int(r[20]);
    whole.dof_mask[i] = std::uint8_t(r[21]);
  }

  // the cracks booked here since the last gather
  const auto& cracks = local_->cracks();
  mine.clear();
  for (std::size_t c = cracks_gathered_; c < cracks.size(); ++c)
  {
    const dem::CrackEvent& e = cracks[c];
    mine.insert(mine.end(),
                {e.time, double(e.a), double(e.b), e.midpoint[0], e.midpoint[1], e.midpoint[2],
                 e.axis[0], e.axis[1], e.axis[2], double(e.mode), e.energy});
  }
  cracks_gathered_ = cracks.size();
  gathered = gather_on_root(mine, comm_);
  std::vector<dem::CrackEvent> arrived;
  for (std::size_t at = 0; at < gathered.size(); at += crack_doubles)
  {
    const double* r = &gathered[at];
    dem::CrackEvent e;
    e.time = r[0], e.a = int(r[1]), e.b = int(r[2]);
    e.midpoint = Vec3(r[3], r[4], r[5]), e.axis = Vec3(r[6], r[7], r[8]);
    e.mode = dem::CrackMode(int(r[9])), e.energy = r[10];
    const auto ga = global_of_user_[std::size_t(e.a)], gb = global_of_user_[std::size_t(e.b)];
    e.bond = bond_index_.at(pair_key(ga, gb));
    arrived.push_back(e);
  }
  // the order one rank logs them in: by time, within a step by particle ids
  std::stable_sort(arrived.begin(), arrived.end(),
                   [](const dem::CrackEvent& x, const dem::CrackEvent& y)
                   { return std::tuple(x.time, x.a, x.b) < std::tuple(y.time, y.a, y.b); });

  if (all && particles_.bonds().has_failure()) // (the model of a rank > 0 may be freed)
    gather_bond_states(false);
  if (!root_)
    return;
  auto state = report_->take_running_state();
  state.time = time(), state.steps = steps();
  state.energy = energy_, state.max_speed = max_speed_, state.unbalanced = unbalanced_;
  state.unbalanced_ratio = unbalanced_ratio_;
  state.broken_by_mode = broken_by_mode_;
  for (std::size_t k = 0; k < state.applied_pressure.size(); ++k) // the same on every rank
    state.applied_pressure[k] = local_->applied_pressure(k);
  dem::BondStore& whole_bonds = model_.bonds;
  for (const auto& e : arrived)
  {
    // a broken bond whose ends drifted apart is no rank's to report: the log says it broke
    whole_bonds.state[e.bond] = dem::BondState::broken;
    whole_bonds.damage[e.bond] = 1.0;
    whole_bonds.dissipated[e.bond] = e.energy;
    state.cracks.push_back(e);
  }
  report_->set_running_state(std::move(state));
}

void DistributedSolver::share_ghost_references()
{
  dem::ParticleStore& p = particles_.particles();
  const auto& ids = particles_.global_ids();
  const std::size_t owned = particles_.n_owned();
  // every rank's ghosts to every rank, each answered by its owner (snapshots only: O(ghosts))
  const std::vector<std::int64_t> wanted(ids.begin() + long(owned), ids.end());
  const auto all_wanted = dealii::Utilities::MPI::all_gather(comm_, wanted);
  std::unordered_map<std::int64_t, std::size_t> local;
  for (std::size_t i = 0; i < owned; ++i)
    local.emplace(ids[i], i);
  std::vector<double> answers;
  for (const auto& ghosts_of_rank : all_wanted)
    for (const std::int64_t id : ghosts_of_rank)
      if (const auto it = local.find(id); it != local.end())
      {
        const Vec3& x = p.reference_position[it->second];
        answers.insert(answers.end(), {double(id), x[0], x[1], x[2]});
      }
  local.clear();
  for (std::size_t i = owned; i < p.size(); ++i)
    local.emplace(ids[i], i);
  for (const auto& from_rank : dealii::Utilities::MPI::all_gather(comm_, answers))
    for (std::size_t at = 0; at < from_rank.size(); at += 4)
      if (const auto it = local.find(std::int64_t(from_rank[at])); it != local.end())
        p.reference_position[it->second] =
            Vec3(from_rank[at + 1], from_rank[at + 2], from_rank[at + 3]);
}
} // namespace dembridge::distributed
