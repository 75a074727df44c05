// Contacts on several MPI ranks (contact_forces.h): the histories by global ids, and the figures
// the ranks sum. A contact's history is (xi, theta, kt, kr) of its pair or sphere-wall contact,
// in the pair's global-id orientation; every rank that computed a pair holds the same bits, so
// a receiver keeps any one copy.
#include "dem/contacts/contact_forces.h"
#include <algorithm>
#include <numeric>

namespace dembridge::dem
{
namespace
{
/// A pair's key: (lower id, upper id); a sphere-wall contact's: (-1 - wall, id).
std::array<std::int64_t, 2> pair_key(std::int64_t a, std::int64_t b)
{
  return {std::min(a, b), std::max(a, b)};
}
} // namespace

void ContactForces::distribute(std::size_t owned, const std::vector<std::int64_t>& global_ids,
                               const std::vector<double>& history)
{
  owned_ = owned;
  global_id_ = &global_ids;
  list_.invalidate();
  wall_of_.clear(), wall_particle_.clear(), wall_xi_.clear(), wall_theta_.clear();
  wall_kt_.clear(), wall_kr_.clear();
  history_in_ = history;
  history_key_.clear();
  const std::size_t n = history_in_.size() / history_record_size;
  history_key_.reserve(n);
  for (std::size_t r = 0; r < n; ++r)
  {
    const double* h = &history_in_[r * history_record_size];
    history_key_.push_back({{std::int64_t(h[0]), std::int64_t(h[1])}, r});
  }
  std::sort(history_key_.begin(), history_key_.end());
}

void ContactForces::take_distributed_history()
{
  auto find = [&](const std::array<std::int64_t, 2>& key) -> const double*
  {
    const auto at =
        std::lower_bound(history_key_.begin(), history_key_.end(), std::pair(key, std::size_t(0)));
    return at != history_key_.end() && at->first == key
               ? &history_in_[at->second * history_record_size]
               : nullptr;
  };
  auto take = [](const double* h, Vec3& xi, Vec3& theta, double& kt, double& kr)
  {
    xi = Vec3(h[2], h[3], h[4]);
    theta = Vec3(h[5], h[6], h[7]);
    kt = h[8], kr = h[9];
  };
  const auto& ids = *global_id_;
  const auto& first = list_.first();
  const auto& second = list_.second();
  for (std::size_t k = 0; k < first.size(); ++k)
    if (const double* h = find(pair_key(ids[std::size_t(first[k])], ids[std::size_t(second[k])])))
      take(h, xi_[k], theta_[k], kt_[k], kr_[k]);
  for (std::size_t e = 0; e < wall_of_.size(); ++e)
    if (const double* h = find({-1 - wall_of_[e], ids[std::size_t(wall_particle_[e])]}))
      take(h, wall_xi_[e], wall_theta_[e], wall_kt_[e], wall_kr_[e]);
  history_key_.clear();
}

void ContactForces::export_history(std::vector<double>& out) const
{
  // contacts never spread over ranks (one store's, read from a one-rank checkpoint) are keyed
  // by their store's indices, which are the model's
  std::vector<std::int64_t> own;
  if (!global_id_)
  {
    int largest = -1;
    for (const auto* indices : {&list_.first(), &list_.second(), &wall_particle_})
      for (const auto i : *indices)
        largest = std::max(largest, int(i));
    own.resize(std::size_t(largest + 1));
    std::iota(own.begin(), own.end(), std::int64_t(0));
  }
  const auto& ids = global_id_ ? *global_id_ : own;
  auto put =
      [&](std::int64_t a, std::int64_t b, const Vec3& xi, const Vec3& theta, double kt, double kr)
  {
    out.insert(out.end(),
               {double(a), double(b), xi[0], xi[1], xi[2], theta[0], theta[1], theta[2], kt, kr});
  };
  const auto& first = list_.first();
  const auto& second = list_.second();
  for (std::size_t k = 0; k < first.size(); ++k)
    if (kt_[k] != 0 || kr_[k] > 0) // touching, or a joint's pair apart after its hand-over
    {
      const auto key = pair_key(ids[std::size_t(first[k])], ids[std::size_t(second[k])]);
      put(key[0], key[1], xi_[k], theta_[k], kt_[k], kr_[k]);
    }
  for (std::size_t e = 0; e < wall_of_.size(); ++e)
    if (wall_kt_[e] > 0 || wall_kr_[e] > 0)
      put(-1 - wall_of_[e], ids[std::size_t(wall_particle_[e])], wall_xi_[e], wall_theta_[e],
          wall_kt_[e], wall_kr_[e]);
}

void ContactForces::figures(double* out) const
{
  out[0] = double(n_active_), out[1] = double(contact_updates_), out[2] = double(list_.builds());
  out[3] = search_seconds_, out[4] = contact_seconds_, out[5] = activation_;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    std::copy(wall_force_[w].data(), wall_force_[w].data() + 3, out + 6 + 3 * w);
}

void ContactForces::set_figures(const double* sums, double time)
{
  n_active_ = std::size_t(sums[0]), contact_updates_ = long(sums[1]);
  reported_builds_ = long(sums[2]);
  search_seconds_ = sums[3], contact_seconds_ = sums[4], activation_ = sums[5];
  for (std::size_t w = 0; w < walls_.size(); ++w)
    wall_force_[w] = Vec3(sums[6 + 3 * w], sums[7 + 3 * w], sums[8 + 3 * w]);
  if (platens_.enabled)
    update_platens(time);
}
} // namespace dembridge::dem
