#include "distributed/run_checkpoint.h"
#include <algorithm>
#include <array>
#include <numeric>

namespace dembridge::distributed
{
namespace
{
/// The fields of ContactForces::visit_state that are sums over the ranks: each rank books its
/// share of the energies, the walls' forces and the counts. Keys that start with one of these.
constexpr std::array<const char*, 8> summed_fields{
    {"contacts/energy/",
     "contacts/walls/force", // also force_previous
     "contacts/walls/damping_force", "contacts/active", "contacts/contact_updates",
     "contacts/search_seconds", "contacts/contact_seconds", "contacts/neighbour_list/builds"}};
/// The walls' positions: the same on every rank (their motion is prescribed); rank 0's.
constexpr std::array<const char*, 2> copied_fields{
    {"contacts/walls/point", "contacts/walls/offset_built"}};

bool summed(const std::string& key)
{
  return std::any_of(summed_fields.begin(), summed_fields.end(),
                     [&](const char* f) { return key.rfind(f, 0) == 0; });
}

/// A summed field's numbers as doubles (counts are below 2^53).
std::vector<double> as_doubles(const FieldArchive::Value& value)
{
  return std::visit(
      [](const auto& v) -> std::vector<double>
      {
        using T = std::decay_t<decltype(v)>;
        std::vector<double> out;
        if constexpr (std::is_same_v<T, std::vector<dem::Vec3>>)
          for (const auto& x : v)
            out.insert(out.end(), {x[0], x[1], x[2]});
        else if constexpr (std::is_same_v<T, std::vector<double>> ||
                           std::is_same_v<T, std::vector<std::int64_t>>)
          for (const auto x : v)
            out.push_back(double(x));
        else
          throw std::logic_error("sum_contact_state: a summed field that is not a number");
        return out;
      },
      value);
}

/// Sets a summed field from @p x (as many doubles as as_doubles gave); returns the count.
std::size_t set_doubles(FieldArchive::Value& value, const double* x)
{
  return std::visit(
      [&](auto& v) -> std::size_t
      {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::vector<dem::Vec3>>)
        {
          for (std::size_t k = 0; k < v.size(); ++k)
            v[k] = dem::Vec3(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
          return 3 * v.size();
        }
        else if constexpr (std::is_same_v<T, std::vector<double>> ||
                           std::is_same_v<T, std::vector<std::int64_t>>)
        {
          for (std::size_t k = 0; k < v.size(); ++k)
            v[k] = typename T::value_type(x[k]);
          return v.size();
        }
        else
          throw std::logic_error("sum_contact_state: a summed field that is not a number");
      },
      value);
}
} // namespace

std::string FieldArchive::where() const
{
  std::string path;
  for (const auto& p : path_)
    path += p + "/";
  return path;
}

void ContactCheckpoint::visit_state(dem::StateArchive& a)
{
  if (one_rank_layout_ && a.loading())
  {
    whole_.visit_state(a);
    history_.clear();
    whole_.export_history(history_); // by the model's indices (never spread: no global ids)
    return;
  }
  {
    dem::StateGroup group(a, "ranks");
    a.io("contact_history", history_);
    if (a.loading() && history_.size() % dem::ContactForces::history_record_size != 0)
      throw dem::InputError(a.where() + "contact_history: not whole records of " +
                            std::to_string(dem::ContactForces::history_record_size) + " values");
  }
  whole_.visit_state(a);
}

std::vector<double> gather_on_root(const std::vector<double>& mine, MPI_Comm comm)
{
  const unsigned n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  const int count = int(mine.size());
  std::vector<int> counts(root ? n_ranks : 0), offsets(root ? n_ranks : 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<double> all;
  if (root)
  {
    for (unsigned r = 1; r < n_ranks; ++r)
      offsets[r] = offsets[r - 1] + counts[r - 1];
    all.resize(std::size_t(offsets.back() + counts.back()));
  }
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
              0, comm);
  return all;
}

std::vector<double> gather_contact_history(const std::vector<double>& mine, MPI_Comm comm)
{
  const std::vector<double> all = gather_on_root(mine, comm);
  constexpr std::size_t size = dem::ContactForces::history_record_size;
  const std::size_t n = all.size() / size;
  // a pair with an end on two ranks comes from both, the same bits: one copy, by key
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](std::size_t r) { return std::pair(all[r * size], all[r * size + 1]); };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return key(x) < key(y); });
  std::vector<double> out;
  out.reserve(all.size());
  for (std::size_t k = 0; k < n; ++k)
    if (k == 0 || key(order[k]) != key(order[k - 1]))
      out.insert(out.end(), all.begin() + long(order[k] * size),
                 all.begin() + long((order[k] + 1) * size));
  return out;
}

void sum_contact_state(dem::ContactForces& rank, dem::ContactForces* whole, MPI_Comm comm)
{
  FieldArchive mine;
  rank.visit_state(mine);
  std::vector<double> values;
  for (const auto& [key, value] : mine.fields())
    if (summed(key))
    {
      const std::vector<double> v = as_doubles(value);
      values.insert(values.end(), v.begin(), v.end());
    }
  const std::vector<double> all = gather_on_root(values, comm);
  if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
    return;
  std::vector<double> sums(values.size(), 0.0); // in rank order, as the energies
  for (std::size_t r = 0; r < all.size() / std::max<std::size_t>(1, values.size()); ++r)
    for (std::size_t k = 0; k < values.size(); ++k)
      sums[k] += all[r * values.size() + k];
  FieldArchive target;
  whole->visit_state(target);
  std::size_t at = 0;
  for (auto& [key, value] : target.fields())
    if (summed(key))
      at += set_doubles(value, sums.data() + at);
  for (const char* key : copied_fields)
    target.fields().at(key) = mine.fields().at(key);
  target.start_loading();
  whole->visit_state(target);
}

void zero_contact_sums(dem::ContactForces& contacts)
{
  FieldArchive state;
  contacts.visit_state(state);
  for (auto& [key, value] : state.fields())
    if (summed(key))
    {
      const std::vector<double> zeros(as_doubles(value).size(), 0.0);
      set_doubles(value, zeros.data());
    }
  state.start_loading();
  contacts.visit_state(state);
}
} // namespace dembridge::distributed
