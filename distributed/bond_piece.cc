#include "distributed/bond_piece.h"
#include "distributed/bond_records.h"
#include "distributed/distributed_particles.h"
#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace dembridge::distributed
{
namespace
{
/// A far end: its user id and position (a broken bond reads nothing else of it).
struct FarEnd
{
  std::int32_t user_id;
  dem::Vec3 position;
};

/// The owners' answers for the far ends of every rank's detached bonds (collective): global id
/// -> user id and position.
std::unordered_map<std::int64_t, FarEnd>
far_ends(const DistributedParticles& d, const std::vector<double>& detached, std::size_t size)
{
  std::vector<std::int64_t> wanted;
  for (std::size_t at = 0; at < detached.size(); at += size)
    wanted.push_back(record_b(&detached[at]));
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  const auto& ids = d.global_ids();
  const dem::ParticleStore& p = d.particles();
  std::unordered_map<std::int64_t, std::size_t> owned;
  for (std::size_t i = 0; i < d.n_owned(); ++i)
    owned.emplace(ids[i], i);
  std::vector<double> answers;
  for (const auto& of_rank : dealii::Utilities::MPI::all_gather(d.communicator(), wanted))
    for (const std::int64_t id : of_rank)
      if (const auto it = owned.find(id); it != owned.end())
      {
        const dem::Vec3& x = p.position[it->second];
        answers.insert(answers.end(), {double(id), double(p.id[it->second]), x[0], x[1], x[2]});
      }
  std::unordered_map<std::int64_t, FarEnd> found;
  for (const auto& from_rank : dealii::Utilities::MPI::all_gather(d.communicator(), answers))
    for (std::size_t at = 0; at < from_rank.size(); at += 5)
      found.emplace(std::int64_t(from_rank[at]),
                    FarEnd{std::int32_t(from_rank[at + 1]),
                           dem::Vec3(from_rank[at + 2], from_rank[at + 3], from_rank[at + 4])});
  return found;
}

/// Sets the arrays of BondPiece::ends for @p n ends.
void resize_ends(dem::ParticleStore& p, std::size_t n)
{
  p.position.resize(n), p.orientation.resize(n, dem::Quat::Identity());
  p.velocity.resize(n, dem::Vec3::Zero()), p.angular_velocity.resize(n, dem::Vec3::Zero());
  p.id.resize(n);
}
} // namespace

BondPiece bond_piece(const DistributedParticles& d)
{
  const dem::ParticleStore& p = d.particles();
  const dem::BondStore& b = d.bonds();
  const auto& ids = d.global_ids();
  const std::size_t size = bond_record_size(b);
  // the bonds booked here as records (global ids of their ends), then the detached ones
  std::vector<double> records;
  for (std::size_t k = 0; k < b.size(); ++k)
    if (std::size_t(b.a[k]) < d.n_owned())
    {
      records.resize(records.size() + size);
      pack_bond(b, k, ids[std::size_t(b.a[k])], ids[std::size_t(b.b[k])], d.bond_id(k),
                &records[records.size() - size]);
    }
  const std::vector<double>& detached = d.detached_bonds();
  records.insert(records.end(), detached.begin(), detached.end());
  const std::unordered_map<std::int64_t, FarEnd> far = far_ends(d, detached, size);
  const std::size_t n_bonds = records.size() / size;

  // the ends, in the order of their user ids
  std::unordered_map<std::int64_t, std::size_t> local;
  for (std::size_t i = 0; i < p.size(); ++i)
    local.emplace(ids[i], i);
  std::vector<std::int64_t> end_ids; // global
  for (std::size_t r = 0; r < n_bonds; ++r)
    end_ids.push_back(record_a(&records[r * size])),
        end_ids.push_back(record_b(&records[r * size]));
  std::sort(end_ids.begin(), end_ids.end());
  end_ids.erase(std::unique(end_ids.begin(), end_ids.end()), end_ids.end());
  auto far_end = [&](std::int64_t id) -> const FarEnd&
  {
    if (const auto f = far.find(id); f != far.end())
      return f->second;
    throw std::logic_error("bond_piece: no rank owns particle " + std::to_string(id));
  };
  std::vector<std::pair<std::int32_t, std::int64_t>> by_user; // (user id, global id)
  for (const std::int64_t id : end_ids)
  {
    const auto it = local.find(id);
    by_user.emplace_back(it != local.end() ? p.id[it->second] : far_end(id).user_id, id);
  }
  std::sort(by_user.begin(), by_user.end());
  BondPiece piece;
  dem::ParticleStore& e = piece.ends;
  resize_ends(e, by_user.size());
  std::unordered_map<std::int64_t, std::int32_t> end_of; // global id -> index in ends
  for (std::size_t j = 0; j < by_user.size(); ++j)
  {
    const auto [user, id] = by_user[j];
    e.id[j] = user;
    end_of.emplace(id, std::int32_t(j));
    if (const auto it = local.find(id); it != local.end())
    {
      const std::size_t i = it->second;
      e.position[j] = p.position[i], e.orientation[j] = p.orientation[i];
      e.velocity[j] = p.velocity[i], e.angular_velocity[j] = p.angular_velocity[i];
    }
    else
      e.position[j] = far_end(id).position;
  }

  // the bonds, in the order of their ids
  std::vector<std::size_t> order(n_bonds);
  std::iota(order.begin(), order.end(), 0);
  auto id_of = [&](std::size_t r) { return record_id(&records[r * size]); };
  std::sort(order.begin(), order.end(),
            [&](std::size_t x, std::size_t y) { return id_of(x) < id_of(y); });
  piece.bonds.failure = b.failure;
  piece.bonds.drop_force_records();
  piece.bonds.reserve(n_bonds);
  for (const std::size_t r : order)
  {
    const double* rec = &records[r * size];
    unpack_bond(rec, piece.bonds, end_of.at(record_a(rec)), end_of.at(record_b(rec)));
    piece.ids.push_back(record_id(rec));
  }
  piece.classes = d.bond_classes();
  return piece;
}
} // namespace dembridge::distributed
