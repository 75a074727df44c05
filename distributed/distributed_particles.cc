#include "distributed/distributed_particles.h"
#include "distributed/bond_records.h"
#include "distributed/particle_records.h"
#include <algorithm>
#include <cmath>
#include <deal.II/base/index_set.h>
#include <map>
#include <numeric>
#include <unordered_map>

namespace dembridge::distributed
{
namespace
{
using dem::Vec3;

/// What a particle carries in the handler beside its location: its slot, the index of the
/// per-step exchange (each rank's owned particles numbered contiguously at a rebuild), and its
/// user id (a ghost's crack log entry names it). Nothing else: the rest of its state travels
/// only when it changes ranks (particle_records.h), and a ghost needs only its owner's kinematics.
namespace handler_property
{
constexpr unsigned slot = 0, user_id = 1, radius = 2, mass = 3; // the last two with contacts
}

/// Kinematics a ghost takes from its owner each step: x, v, w (3 each), q (x, y, z, w).
constexpr std::size_t kinematics = 13;

/// Weight of a cell in the mesh partition: one for the cell, this for each of its particles
/// (the particles' bonds are the work; an empty margin cell costs next to nothing: with a
/// hundred, the empty cells of a mesh over a flight held a tenth of the weight, and a rank with
/// many of them as many fewer particles).
constexpr unsigned particle_weight = 1000;

dealii::Point<3> point(const Vec3& x)
{
  return {x[0], x[1], x[2]};
}

Vec3 vec(const dealii::Point<3>& x)
{
  return {x[0], x[1], x[2]};
}

/// Collective: throws on every rank with @p message when some rank has @p failed.
void throw_if_any(bool failed, const std::string& message, MPI_Comm comm)
{
  if (dealii::Utilities::MPI::max(failed ? 1 : 0, comm) > 0)
    throw std::runtime_error(message);
}

/// FNV-1a over the bytes of the model's particles and bonds: every rank must hold the same model.
std::uint64_t model_checksum(const dem::Model& m)
{
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&](const auto& v)
  {
    const auto* bytes = reinterpret_cast<const unsigned char*>(v.data());
    for (std::size_t i = 0; i < v.size() * sizeof(v[0]); ++i)
      h = (h ^ bytes[i]) * 1099511628211ull;
  };
  add(m.particles.position), add(m.particles.radius), add(m.particles.mass);
  add(m.bonds.a), add(m.bonds.b), add(m.bonds.kn), add(m.bonds.state);
  return h;
}
} // namespace

std::string smooth_joints_on_ranks(const dem::BondStore& bonds)
{
  if (bonds.sliding_joints && bonds.sliding_joints->has_boundaries())
    return "Bond class grain_boundary/joint friction: not available in a distributed (MPI) run "
           "yet; run it on one rank";
  if (!bonds.has_smooth_joints())
    return {};
  const char* bond_class = bonds.has_plane_joints() ? "weak_plane" : "basal";
  return std::string("Bond class ") + bond_class +
         "/smooth joint: not available in a distributed (MPI) run yet; run it on one rank";
}

DistributedParticles::DistributedParticles(const dem::Model& model, const BackgroundGrid& grid,
                                           MPI_Comm comm)
    : comm_(comm), grid_(grid), tria_(comm)
{
  {
    const std::uint64_t mine = model_checksum(model);
    throw_if_any(dealii::Utilities::MPI::min(mine, comm) != dealii::Utilities::MPI::max(mine, comm),
                 "the MPI ranks built different models (every rank builds the case: a packing "
                 "that differs between processes?)",
                 comm);
  }
  create_background_mesh(tria_, grid_);
  const dem::ParticleStore& p = model.particles;
  n_global_ = std::int64_t(p.size());
  skin_ = 0.5 * grid_.cell_width;
  if (!model.contributions.empty())
  {
    // A particle q outside the ghost layer lies at least a cell width w from every owned one
    // at a rebuild; both travel at most skin_ until the next: w - 2 skin_ >= 2 R_max keeps
    // them apart.
    n_properties_ = 4;
    const double r_max =
        p.radius.empty() ? 0.0 : *std::max_element(p.radius.begin(), p.radius.end());
    const double cut_off = 2.0 * r_max;
    if (!(grid_.cell_width > 1.25 * cut_off))
      throw dem::InputError(
          "Contacts/model: the background cells (" + std::to_string(grid_.cell_width) +
          " m) are not wider than 1.25 times the contact cut-off (twice the largest radius, " +
          std::to_string(cut_off) + " m): a contact could reach past the ranks' ghost layer");
    skin_ = std::min(skin_, 0.5 * (grid_.cell_width - cut_off));
  }
  // the particles of each grid cell (a counting sort by cell)
  const std::size_t n_cells = grid_.n_cells();
  std::vector<std::size_t> first(n_cells + 1, 0), by_cell(p.size());
  std::vector<long> cell(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    cell[i] = grid_.cell_of(p.position[i]);
    if (cell[i] < 0)
      throw std::logic_error("DistributedParticles: a particle outside the background grid");
    ++first[std::size_t(cell[i]) + 1];
  }
  std::partial_sum(first.begin(), first.end(), first.begin());
  {
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < p.size(); ++i)
      by_cell[next[std::size_t(cell[i])]++] = i;
  }
  auto grid_cell = [&](const auto& c) { return std::size_t(grid_.cell_of(vec(c->center()))); };
  // balance the particles, not the cells (step-68)
  auto weights = tria_.signals.weight.connect(
      [&](const auto& c, const auto) -> unsigned
      {
        const std::size_t k = grid_cell(c);
        return 1 + particle_weight * unsigned(first[k + 1] - first[k]);
      });
  tria_.repartition();
  weights.disconnect();
  handler_.initialize(tria_, mapping_, n_properties_);
  handler_.signals.particle_lost.connect([this](const auto&, const auto&) { ++n_lost_; });

  std::vector<std::uint32_t> group_mask(p.size(), 0);
  for (std::size_t g = 0; g < model.groups.size() && g < 32; ++g)
    for (const int i : model.groups[g].members)
      group_mask[std::size_t(i)] |= 1u << g;
  std::vector<char> owned(p.size(), 0);
  double props[4] = {0, 0, 0, 0};
  for (const auto& c : tria_.active_cell_iterators())
  {
    if (!c->is_locally_owned())
      continue;
    const std::size_t k = grid_cell(c);
    for (std::size_t j = first[k]; j < first[k + 1]; ++j)
    {
      const std::size_t i = by_cell[j];
      props[handler_property::user_id] = p.id[i];
      props[handler_property::radius] = p.radius[i];
      props[handler_property::mass] = p.mass[i];
      const dealii::Point<3> x = point(p.position[i]);
      handler_.insert_particle(x, mapping_.transform_real_to_unit_cell(c, x),
                               dealii::types::particle_index(i), c,
                               dealii::ArrayView<const double>(props, n_properties_));
      owned[i] = 1;
    }
  }
  handler_.update_cached_numbers();
  // the bonds with an owned end, as records
  if (const std::string why = smooth_joints_on_ranks(model.bonds); !why.empty())
    throw dem::InputError(why);
  bonds_.failure = model.bonds.failure;
  bonds_.drop_force_records();
  bond_classes_ = !model.bonds.bond_class.empty();
  const std::size_t size = bond_record_size(bonds_);
  std::vector<double> records;
  for (std::size_t k = 0; k < model.bonds.size(); ++k)
  {
    const auto a = std::size_t(model.bonds.a[k]), b = std::size_t(model.bonds.b[k]);
    if (!owned[a] && !owned[b])
      continue;
    records.resize(records.size() + size);
    pack_bond(model.bonds, k, std::int64_t(a), std::int64_t(b), std::int64_t(k),
              &records[records.size() - size]);
  }
  std::vector<double> packed(state::count);
  build_local(records,
              [&](std::int64_t id, std::size_t i)
              {
                const auto m = std::size_t(id);
                pack_state(p, m, id, group_mask[m], Reaction{}, packed.data());
                return unpack_state(packed.data(), particles_, i);
              });
}

void DistributedParticles::build_local(std::vector<double>& records, const FillOwned& fill)
{
  // Owned particles in the order of their global ids (the model's spatial order: the bond
  // loop's memory locality), numbered by slots contiguous over the ranks; the slots travel to
  // the ghosts with the ghost exchange.
  using Entry = std::pair<std::int64_t, dealii::Particles::ParticleIterator<3>>;
  auto by_key = [](const Entry& x, const Entry& y) { return x.first < y.first; };
  auto owned_entries = [&]
  {
    std::vector<Entry> owned;
    owned.reserve(handler_.n_locally_owned_particles());
    for (auto it = handler_.begin(); it != handler_.end(); ++it)
      owned.emplace_back(std::int64_t(it->get_id()), it);
    std::sort(owned.begin(), owned.end(), by_key);
    return owned;
  };
  std::vector<Entry> owned = owned_entries();
  n_owned_ = owned.size();
  std::int64_t offset = 0, count = std::int64_t(n_owned_);
  MPI_Exscan(&count, &offset, 1, MPI_INT64_T, MPI_SUM, comm_);
  if (dealii::Utilities::MPI::this_mpi_process(comm_) == 0)
    offset = 0; // MPI_Exscan leaves rank 0's result undefined
  first_slot_ = offset;
  for (std::size_t k = 0; k < n_owned_; ++k)
    owned[k].second->get_properties()[handler_property::slot] = double(offset + std::int64_t(k));
  handler_.exchange_ghost_particles(false);
  owned = owned_entries(); // (iterators taken anew after the handler changed)
  std::vector<Entry> ghosts;
  for (auto it = handler_.begin_ghost(); it != handler_.end_ghost(); ++it)
    ghosts.emplace_back(std::int64_t(it->get_properties()[handler_property::slot]), it);
  std::sort(ghosts.begin(), ghosts.end(), by_key); // the partitioner's order
  const std::size_t n = n_owned_ + ghosts.size();
  particles_ = {};
  resize(particles_, n);
  global_id_.resize(n);
  global_id_.shrink_to_fit();
  reactions_.clear();
  for (std::size_t k = 0; k < n_owned_; ++k)
  {
    particles_.position[k] = vec(owned[k].second->get_location());
    const Reaction r = fill(owned[k].first, k);
    if (r != Reaction{})
      reactions_.emplace_back(std::uint32_t(k), r);
    global_id_[k] = owned[k].first;
  }
  for (std::size_t j = 0; j < ghosts.size(); ++j)
  {
    const auto& it = ghosts[j].second;
    const std::size_t i = n_owned_ + j;
    particles_.position[i] = vec(it->get_location());
    const auto props = it->get_properties();
    particles_.id[i] = std::int32_t(props[handler_property::user_id]);
    if (with_contacts())
      particles_.radius[i] = props[handler_property::radius],
      particles_.mass[i] = props[handler_property::mass];
    global_id_[i] = std::int64_t(it->get_id());
  }
  rebuilt_at_.assign(particles_.position.begin(), particles_.position.begin() + long(n_owned_));

  // Bonds: one copy of each record, those with an owned end, between local indices; a bonded
  // pair must have both ends here (the ghost layer is one cell deep: the cells are at least
  // the cut-off wide), a broken one whose far end left carries nothing and is kept aside by
  // the owner of its end a (detached_bonds: the bond files list it).
  std::unordered_map<std::int64_t, std::int32_t> local;
  local.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    local.emplace(global_id_[i], std::int32_t(i));
  HeldBonds held = hold_bonds(records, bonds_.failure, local, n_owned_);
  throw_if_any(!held.too_long.empty(),
               "a bond (between particles " + held.too_long +
                   " on some rank) grew longer than a background cell: its ends are no longer "
                   "in touching cells",
               comm_);
  bonds_ = std::move(held.bonds);
  bond_ids_ = std::move(held.ids);
  detached_ = std::move(held.detached);

  // The per-step exchange: 13 doubles a particle at 13 slot + c; owned slots are contiguous.
  const auto n_slots =
      dealii::types::global_dof_index(dealii::Utilities::MPI::sum(std::uint64_t(n_owned_), comm_));
  dealii::IndexSet owned_set(kinematics * n_slots), ghost_set(kinematics * n_slots);
  owned_set.add_range(kinematics * dealii::types::global_dof_index(offset),
                      kinematics * dealii::types::global_dof_index(offset + count));
  for (const auto& g : ghosts)
    ghost_set.add_range(kinematics * dealii::types::global_dof_index(g.first),
                        kinematics * dealii::types::global_dof_index(g.first + 1));
  ghost_set.compress();
  partitioner_ =
      std::make_shared<const dealii::Utilities::MPI::Partitioner>(owned_set, ghost_set, comm_);
  ghost_buffer_.assign(kinematics * ghosts.size(), 0.0);
  send_buffer_.assign(partitioner_->n_import_indices(), 0.0);
  requests_.reserve(partitioner_->import_targets().size() + partitioner_->ghost_targets().size());
  update_ghosts(); // the ghosts' kinematics
}

void DistributedParticles::update_ghosts()
{
  // The partitioner's pattern (Partitioner::export_to_ghosted_array_start and _finish), with the
  // owned particles' kinematics packed straight into the send buffer, in the order of the
  // partitioner's import indices (whole particles: 13 entries a slot).
  const auto& p = particles_;
  double* out = send_buffer_.data();
  for (const auto& [begin, end] : partitioner_->import_indices())
    for (unsigned k = begin; k < end; k += kinematics, out += kinematics)
    {
      const std::size_t i = k / kinematics;
      std::copy(p.position[i].data(), p.position[i].data() + 3, out);
      std::copy(p.velocity[i].data(), p.velocity[i].data() + 3, out + 3);
      std::copy(p.angular_velocity[i].data(), p.angular_velocity[i].data() + 3, out + 6);
      std::copy(p.orientation[i].coeffs().data(), p.orientation[i].coeffs().data() + 4, out + 9);
    }
  requests_.clear();
  constexpr int tag = 3217; // the ghost refresh's messages
  std::size_t at = 0;
  for (const auto& [rank, n] : partitioner_->ghost_targets())
  {
    requests_.emplace_back();
    MPI_Irecv(ghost_buffer_.data() + at, int(n), MPI_DOUBLE, int(rank), tag, comm_,
              &requests_.back());
    at += n;
  }
  at = 0;
  for (const auto& [rank, n] : partitioner_->import_targets())
  {
    requests_.emplace_back();
    MPI_Isend(send_buffer_.data() + at, int(n), MPI_DOUBLE, int(rank), tag, comm_,
              &requests_.back());
    at += n;
  }
  MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  const std::size_t n_ghosts = particles_.size() - n_owned_;
  for (std::size_t j = 0; j < n_ghosts; ++j)
  {
    const double* k = &ghost_buffer_[kinematics * j];
    const std::size_t i = n_owned_ + j;
    particles_.position[i] = Vec3(k[0], k[1], k[2]);
    particles_.velocity[i] = Vec3(k[3], k[4], k[5]);
    particles_.angular_velocity[i] = Vec3(k[6], k[7], k[8]);
    std::copy(k + 9, k + 13, particles_.orientation[i].coeffs().data());
  }
}

DistributedParticles::MotionCheck DistributedParticles::check_motion(bool local_unstable)
{
  double moved = 0;
  bool finite = !local_unstable;
  for (std::size_t i = 0; i < n_owned_; ++i)
  {
    const double d2 = (particles_.position[i] - rebuilt_at_[i]).squaredNorm();
    finite = finite && std::isfinite(d2);
    moved = std::max(moved, d2);
  }
  double local[2] = {moved, finite ? 0.0 : 1.0}, global[2];
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, comm_);
  return {global[0] > skin_ * skin_, global[1] > 0};
}

void DistributedParticles::rebuild(const Reactions& reactions, std::vector<double>& contacts,
                                   std::size_t contact_record_size)
{
  ++n_rebuilds_;
  // 1. the owned particles' locations into the handler (slot - the first slot = local index)
  for (auto it = handler_.begin(); it != handler_.end(); ++it)
  {
    const auto i =
        std::size_t(std::int64_t(it->get_properties()[handler_property::slot]) - first_slot_);
    it->set_location(point(particles_.position[i]));
  }
  // 2. the bonds held, by global ids; the ids owned until now (sorted: owned particles are in
  // the order of their ids)
  const std::size_t size = bond_record_size(bonds_);
  std::vector<double> records(size * bonds_.size());
  for (std::size_t k = 0; k < bonds_.size(); ++k)
    pack_bond(bonds_, k, global_id_[std::size_t(bonds_.a[k])], global_id_[std::size_t(bonds_.b[k])],
              bond_id(k), &records[k * size]);
  records.insert(records.end(), detached_.begin(), detached_.end()); // they go with end a
  const std::size_t n_held = records.size() / size;
  const std::vector<std::int64_t> was_owned(global_id_.begin(),
                                            global_id_.begin() + long(n_owned_));
  auto index_in = [](const std::vector<std::int64_t>& sorted, std::int64_t id) -> long
  {
    const auto at = std::lower_bound(sorted.begin(), sorted.end(), id);
    return at != sorted.end() && *at == id ? long(at - sorted.begin()) : -1;
  };
  auto reaction_of = [&](std::size_t i)
  {
    const auto at = std::lower_bound(
        reactions.begin(), reactions.end(), std::pair(std::uint32_t(i), Reaction{}),
        [](const auto& x, const auto& y) { return x.first < y.first; });
    return at != reactions.end() && at->first == i ? at->second : Reaction{};
  };
  // 3. the handler moves particles into their new cells and ranks
  handler_.sort_particles_into_subdomains_and_cells();
  throw_if_any(n_lost_ > 0,
               "a particle left the background mesh, or moved more than a cell between two "
               "migrations",
               comm_);
  repartition_if_imbalanced();
  // 4. a particle that left (to a neighbour's cell, or with its cell in a repartition): its
  // state and each of its bonds go to its new owner
  std::vector<std::int64_t> now_owned;
  now_owned.reserve(handler_.n_locally_owned_particles());
  for (auto it = handler_.begin(); it != handler_.end(); ++it)
    now_owned.push_back(std::int64_t(it->get_id()));
  std::sort(now_owned.begin(), now_owned.end());
  std::vector<std::int64_t> departed;
  std::set_difference(was_owned.begin(), was_owned.end(), now_owned.begin(), now_owned.end(),
                      std::back_inserter(departed));
  const auto ids = dealii::types::global_dof_index(n_global_);
  dealii::IndexSet owned_set(ids), departed_set(ids);
  for (const auto i : now_owned)
    owned_set.add_index(dealii::types::global_dof_index(i));
  for (const auto i : departed)
    departed_set.add_index(dealii::types::global_dof_index(i));
  owned_set.compress(), departed_set.compress();
  const std::vector<unsigned> new_owner =
      dealii::Utilities::MPI::compute_index_owner(owned_set, departed_set, comm_);
  // A message: the numbers of states, bond records and contact records, then the states, the
  // bonds and the contacts. A particle that left takes its state and its bonds and contacts (a
  // pair whose two ends left to two ranks goes to both).
  std::map<unsigned, std::array<std::vector<double>, 3>> parts;
  for (std::size_t d = 0; d < departed.size(); ++d)
  {
    auto& out = parts[new_owner[d]][0];
    const auto i = std::size_t(index_in(was_owned, departed[d]));
    out.resize(out.size() + state::count);
    pack_state(particles_, i, departed[d], particles_.group_mask[i], reaction_of(i),
               &out[out.size() - state::count]);
  }
  auto route =
      [&](const double* rec, std::size_t size, std::int64_t a, std::int64_t b, std::size_t part)
  {
    const long da = a >= 0 ? index_in(departed, a) : -1, db = index_in(departed, b);
    const int to_a = da >= 0 ? int(new_owner[std::size_t(da)]) : -1;
    const int to_b = db >= 0 ? int(new_owner[std::size_t(db)]) : -1;
    for (const int to : {to_a, to_b == to_a ? -1 : to_b})
      if (to >= 0)
      {
        auto& out = parts[unsigned(to)][part];
        out.insert(out.end(), rec, rec + size);
      }
  };
  for (std::size_t k = 0; k < n_held; ++k)
  {
    const double* rec = &records[k * size];
    route(rec, size, record_a(rec), record_b(rec), 1);
  }
  const std::size_t n_contacts = contact_record_size ? contacts.size() / contact_record_size : 0;
  for (std::size_t k = 0; k < n_contacts; ++k)
  {
    const double* rec = &contacts[k * contact_record_size];
    route(rec, contact_record_size, std::int64_t(rec[0]), std::int64_t(rec[1]), 2);
  }
  std::map<unsigned, std::vector<double>> outgoing;
  for (auto& [to, part] : parts)
  {
    auto& out = outgoing[to];
    out = {double(part[0].size() / state::count), double(part[1].size() / size),
           double(contact_record_size ? part[2].size() / contact_record_size : 0)};
    for (const auto& v : part)
      out.insert(out.end(), v.begin(), v.end());
  }
  std::unordered_map<std::int64_t, std::vector<double>::const_iterator> arrived;
  const auto incoming = dealii::Utilities::MPI::some_to_some(comm_, outgoing);
  for (const auto& [from, message] : incoming)
  {
    (void)from;
    const auto n_states = std::size_t(message[0]), n_bonds = std::size_t(message[1]);
    const auto n_in = std::size_t(message[2]);
    auto at = message.begin() + 3;
    for (std::size_t k = 0; k < n_states; ++k, at += state::count)
      arrived.emplace(std::int64_t(at[state::id]), at);
    records.insert(records.end(), at, at + long(n_bonds * size));
    at += long(n_bonds * size);
    contacts.insert(contacts.end(), at, at + long(n_in * contact_record_size));
  }
  n_arrived_ += long(arrived.size());
  // 5. the stores anew: a particle that stayed from the old store, one that arrived from its
  // message
  const dem::ParticleStore old = std::move(particles_);
  std::vector<double> packed(state::count);
  build_local(records,
              [&](std::int64_t id, std::size_t i)
              {
                if (const long was = index_in(was_owned, id); was >= 0)
                {
                  const auto w = std::size_t(was);
                  pack_state(old, w, id, old.group_mask[w], reaction_of(w), packed.data());
                  return unpack_state(packed.data(), particles_, i);
                }
                return unpack_state(&*arrived.at(id), particles_, i);
              });
}

void DistributedParticles::repartition_if_imbalanced()
{
  const auto n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm_);
  const auto mine = std::uint64_t(handler_.n_locally_owned_particles());
  const auto most = dealii::Utilities::MPI::max(mine, comm_);
  const auto all = dealii::Utilities::MPI::sum(mine, comm_);
  if (n_ranks < 2 || double(most) * n_ranks <= max_imbalance * double(all))
    return;
  ++n_repartitions_;
  largest_imbalance_.first = std::max(largest_imbalance_.first, double(most) * n_ranks / all);
  // the setup's weights with the particles where they are now (only owned cells are asked)
  auto weights = tria_.signals.weight.connect(
      [this](const auto& c, const auto) -> unsigned
      {
        const dealii::Triangulation<3>::active_cell_iterator cell(c);
        return 1 + particle_weight * unsigned(handler_.n_particles_in_cell(cell));
      });
  handler_.prepare_for_coarsening_and_refinement();
  tria_.repartition();
  handler_.unpack_after_coarsening_and_refinement();
  weights.disconnect();
  handler_.update_cached_numbers();
  const auto now =
      dealii::Utilities::MPI::max(std::uint64_t(handler_.n_locally_owned_particles()), comm_);
  largest_imbalance_.second = std::max(largest_imbalance_.second, double(now) * n_ranks / all);
}

std::int64_t DistributedParticles::bond_id(std::size_t k) const
{
  const std::uint64_t key = local_pair(bonds_.a[k], bonds_.b[k]);
  const auto at =
      std::lower_bound(bond_ids_.begin(), bond_ids_.end(), key,
                       [](const auto& entry, std::uint64_t x) { return entry.first < x; });
  return at->second; // (every bond held has its id: build_local)
}

std::size_t DistributedParticles::halo_doubles() const
{
  return partitioner_->n_import_indices();
}

std::size_t DistributedParticles::halo_targets() const
{
  return partitioner_->import_targets().size();
}

std::size_t DistributedParticles::handler_bytes() const
{
  const std::size_t in_handler =
      handler_.n_locally_owned_particles() + (particles_.size() - n_owned_);
  return in_handler * (7 + n_properties_) * sizeof(double);
}

std::size_t DistributedParticles::memory_bytes() const
{
  auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return particles_.memory_bytes() + bonds_.memory_bytes() + bytes(bond_ids_) + bytes(detached_) +
         bytes(global_id_) + bytes(reactions_) + bytes(rebuilt_at_) + bytes(ghost_buffer_) +
         bytes(send_buffer_) + bytes(requests_) + partitioner_->memory_consumption() +
         mesh_bytes() + handler_bytes();
}
} // namespace dembridge::distributed
