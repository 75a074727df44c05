#include "distributed/bond_records.h"
#include <algorithm>

namespace dembridge::distributed
{
namespace
{
// where a record's fields start (0, 1: the particles' global ids; 2: the bond's)
constexpr std::size_t at_class = 3, at_length = 4, at_axis = 5, at_kn = 8, at_ks = 9, at_ktor = 10,
                      at_kben = 11, at_fraction = 12, at_radius = 13, at_ct = 14, at_cr = 15,
                      at_model = 16, at_state = 17, plain_size = 18;
// with a failure law
constexpr std::size_t at_tensile = 18, at_shear = 19, at_damage = 20, at_kappa_max = 21,
                      at_kappa_ultimate = 22, at_dissipated = 23, at_mode = 24, failure_size = 25;
} // namespace

std::size_t bond_record_size(const dem::BondStore& b)
{
  return b.has_failure() ? failure_size : plain_size;
}

void pack_bond(const dem::BondStore& b, std::size_t k, std::int64_t ga, std::int64_t gb,
               std::int64_t id, double* out)
{
  out[0] = double(ga), out[1] = double(gb), out[2] = double(id);
  out[at_class] = b.bond_class.empty() ? -1.0 : double(b.bond_class[k]); // -1: no classes
  out[at_length] = b.rest_length[k];
  for (int d = 0; d < 3; ++d)
    out[at_axis + std::size_t(d)] = b.rest_axis[k][d];
  out[at_kn] = b.kn[k], out[at_ks] = b.ks[k], out[at_ktor] = b.ktor[k], out[at_kben] = b.kben[k];
  out[at_fraction] = b.contact_fraction[k], out[at_radius] = b.radius[k];
  out[at_ct] = b.damping_force[k], out[at_cr] = b.damping_moment[k];
  out[at_model] = double(b.model[k]), out[at_state] = double(b.state[k]);
  if (!b.has_failure())
    return;
  out[at_tensile] = b.tensile_strength[k], out[at_shear] = b.shear_strength[k];
  out[at_damage] = b.damage[k], out[at_kappa_max] = b.kappa_max[k];
  out[at_kappa_ultimate] = b.kappa_ultimate[k], out[at_dissipated] = b.dissipated[k];
  out[at_mode] = double(b.failure_mode[k]);
}

bool record_bonded(const double* record)
{
  return dem::is_bonded(dem::BondState(int(record[at_state])));
}

void unpack_bond(const double* r, dem::BondStore& b, std::int32_t a, std::int32_t b_local)
{
  dem::BondStiffness k;
  k.kn = r[at_kn], k.ks = r[at_ks], k.ktor = r[at_ktor], k.kben = r[at_kben];
  k.contact_fraction = r[at_fraction], k.radius = r[at_radius];
  b.add(a, b_local, r[at_length], dem::Vec3(r[at_axis], r[at_axis + 1], r[at_axis + 2]),
        dem::BondModel(int(r[at_model])), k);
  b.damping_force.back() = r[at_ct];
  b.damping_moment.back() = r[at_cr];
  b.state.back() = dem::BondState(int(r[at_state]));
  if (r[at_class] >= 0) // (the solver reads classes only with smooth joints, refused on ranks)
    b.bond_class.push_back(dem::BondClass(int(r[at_class])));
  if (!b.has_failure())
    return;
  b.tensile_strength.push_back(r[at_tensile]);
  b.shear_strength.push_back(r[at_shear]);
  b.damage.push_back(r[at_damage]);
  b.kappa_max.push_back(r[at_kappa_max]);
  b.kappa_ultimate.push_back(r[at_kappa_ultimate]);
  b.dissipated.push_back(r[at_dissipated]);
  b.failure_mode.push_back(dem::CrackMode(int(r[at_mode])));
}

HeldBonds hold_bonds(const std::vector<double>& records, const dem::FailureLaw& failure,
                     const std::unordered_map<std::int64_t, std::int32_t>& local,
                     std::size_t n_owned)
{
  HeldBonds out;
  out.bonds.failure = failure;
  out.bonds.drop_force_records();
  const std::size_t size = bond_record_size(out.bonds);
  const std::size_t n_records = records.size() / size;
  struct Held
  {
    std::int32_t a, b;
    std::size_t record;
  };
  std::vector<Held> held;
  held.reserve(n_records);
  std::vector<std::size_t> detached;
  for (std::size_t r = 0; r < n_records; ++r)
  {
    const double* rec = &records[r * size];
    const auto a = local.find(record_a(rec)), b = local.find(record_b(rec));
    const bool a_owned = a != local.end() && std::size_t(a->second) < n_owned;
    const bool b_owned = b != local.end() && std::size_t(b->second) < n_owned;
    if (!a_owned && !b_owned)
      continue;
    if (a == local.end() || b == local.end())
    {
      if (record_bonded(rec) && out.too_long.empty())
        out.too_long = std::to_string(record_a(rec)) + " and " + std::to_string(record_b(rec));
      else if (!record_bonded(rec) && a_owned)
        detached.push_back(r);
      continue;
    }
    held.push_back({a->second, b->second, r});
  }
  std::stable_sort(held.begin(), held.end(),
                   [](const Held& x, const Held& y)
                   {
                     return std::pair(std::min(x.a, x.b), std::max(x.a, x.b)) <
                            std::pair(std::min(y.a, y.b), std::max(y.a, y.b));
                   });
  held.erase(std::unique(held.begin(), held.end(),
                         [](const Held& x, const Held& y) { return x.a == y.a && x.b == y.b; }),
             held.end());
  out.bonds.reserve(held.size());
  out.ids.reserve(held.size());
  for (const Held& h : held)
  {
    unpack_bond(&records[h.record * size], out.bonds, h.a, h.b);
    out.ids.emplace_back(local_pair(h.a, h.b), record_id(&records[h.record * size]));
  }
  std::sort(out.ids.begin(), out.ids.end());
  // (two ranks may send the same record: one copy)
  auto id_of = [&](std::size_t r) { return record_id(&records[r * size]); };
  std::sort(detached.begin(), detached.end(),
            [&](std::size_t x, std::size_t y) { return id_of(x) < id_of(y); });
  detached.erase(std::unique(detached.begin(), detached.end(),
                             [&](std::size_t x, std::size_t y) { return id_of(x) == id_of(y); }),
                 detached.end());
  for (const std::size_t r : detached)
    out.detached.insert(out.detached.end(), &records[r * size], &records[r * size] + size);
  return out;
}
} // namespace dembridge::distributed
