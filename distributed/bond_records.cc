#include "distributed/bond_records.h"

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
} // namespace dembridge::distributed
