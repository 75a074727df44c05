#include "dem/solvers/run_state.h"
#include <algorithm>
#include <numeric>

namespace dembridge::dem
{
void visit_particles(StateArchive& a, ParticleStore& p)
{
  StateGroup group(a, "particles");
  a.io_sized("position", p.position);
  a.io_sized("reference_position", p.reference_position);
  a.io_sized("velocity", p.velocity);
  a.io_sized("angular_velocity", p.angular_velocity);
  a.io_sized("orientation", p.orientation);
  a.io_sized("force", p.force);
  a.io_sized("torque", p.torque);
  a.io_sized("radius", p.radius);
  a.io_sized("mass", p.mass);
  a.io_sized("inertia", p.inertia);
  a.io_sized("dof_mask", p.dof_mask);
  a.io_sized("group_mask", p.group_mask);
  a.io_sized("coordination", p.coordination);
}

namespace
{
/// Every per-bond array of @p b, in one place for saving and restoring.
void visit_bond_arrays(StateArchive& a, BondStore& b)
{
  a.io("a", b.a);
  a.io("b", b.b);
  a.io("rest_length", b.rest_length);
  a.io("rest_axis", b.rest_axis);
  a.io("kn", b.kn);
  a.io("ks", b.ks);
  a.io("ktor", b.ktor);
  a.io("kben", b.kben);
  a.io("contact_fraction", b.contact_fraction);
  a.io("radius", b.radius);
  a.io("damping_force", b.damping_force);
  a.io("damping_moment", b.damping_moment);
  a.io_enums("model", b.model);
  a.io_enums("state", b.state);
  a.io_enums("bond_class", b.bond_class);
  a.io("force", b.force);
  a.io("moment", b.moment);
  a.io("tensile_strength", b.tensile_strength);
  a.io("shear_strength", b.shear_strength);
  a.io("damage", b.damage);
  a.io("kappa_max", b.kappa_max);
  a.io("kappa_ultimate", b.kappa_ultimate);
  a.io("dissipated", b.dissipated);
  a.io_enums("failure_mode", b.failure_mode);
}

/// The arrays of @p stored must have the lengths the model's have.
void check_lengths(const BondStore& stored, const BondStore& model, const std::string& where)
{
  auto check = [&](const char* name, std::size_t n_stored, std::size_t n_model)
  {
    if (n_stored != n_model)
      throw InputError(where + name + ": " + std::to_string(n_stored) +
                       " entries in the checkpoint, " + std::to_string(n_model) + " in this model");
  };
  const std::size_t n = model.size();
  check("a", stored.a.size(), n);
  for (std::size_t size :
       {stored.b.size(), stored.rest_length.size(), stored.rest_axis.size(), stored.kn.size(),
        stored.ks.size(), stored.ktor.size(), stored.kben.size(), stored.contact_fraction.size(),
        stored.radius.size(), stored.damping_force.size(), stored.damping_moment.size(),
        stored.model.size(), stored.state.size()})
    check("(per-bond arrays)", size, n);
  // force records (output only): checked where the model keeps them; a checkpoint written
  // while runs still kept them resumes into a model without them
  if (model.records_forces())
  {
    check("force", stored.force.size(), model.force.size());
    check("moment", stored.moment.size(), model.moment.size());
  }
  // bond classes: empty without a microstructure, else one entry per bond
  check("bond_class", stored.bond_class.size(), model.bond_class.size());
  // failure arrays: empty without a failure law, else one entry per bond
  check("tensile_strength", stored.tensile_strength.size(), model.tensile_strength.size());
  check("shear_strength", stored.shear_strength.size(), model.shear_strength.size());
  check("damage", stored.damage.size(), model.damage.size());
  check("kappa_max", stored.kappa_max.size(), model.kappa_max.size());
  check("kappa_ultimate", stored.kappa_ultimate.size(), model.kappa_ultimate.size());
  check("dissipated", stored.dissipated.size(), model.dissipated.size());
  check("failure_mode", stored.failure_mode.size(), model.failure_mode.size());
}
} // namespace

std::vector<std::size_t> visit_bonds(StateArchive& a, BondStore& b)
{
  StateGroup group(a, "bonds");
  if (!a.loading())
  {
    visit_bond_arrays(a, b);
    return {};
  }
  BondStore stored;
  visit_bond_arrays(a, stored);
  check_lengths(stored, b, a.where());
  // order[k]: the stored bond joining the pair of this store's bond k (stable for repeated
  // pairs, so the identity whenever the orders agree)
  const std::size_t n = b.size();
  std::vector<std::size_t> by_pair(n);
  std::iota(by_pair.begin(), by_pair.end(), 0);
  auto pair_of = [](const BondStore& s, std::size_t k) { return std::pair(s.a[k], s.b[k]); };
  std::stable_sort(by_pair.begin(), by_pair.end(),
                   [&](std::size_t x, std::size_t y)
                   { return pair_of(stored, x) < pair_of(stored, y); });
  std::vector<std::size_t> order(n), used(n, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto key = pair_of(b, k);
    auto it = std::lower_bound(by_pair.begin(), by_pair.end(), key,
                               [&](std::size_t s, auto v) { return pair_of(stored, s) < v; });
    while (it != by_pair.end() && pair_of(stored, *it) == key && used[*it])
      ++it;
    if (it == by_pair.end() || pair_of(stored, *it) != key)
      throw InputError(a.where() +
                       "a, b: the checkpoint's bonds join other particles than "
                       "this model's (bond of particles " +
                       std::to_string(key.first) + " and " + std::to_string(key.second) +
                       " not found)");
    used[*it] = 1;
    order[k] = *it;
  }
  stored.failure = b.failure;
  stored.smooth_joint_normal = b.smooth_joint_normal; // the case's, as the failure law
  stored.sliding_joints = b.sliding_joints;
  if (!b.records_forces())
    stored.drop_force_records();
  stored.reorder(order);
  stored.basal_normal = b.basal_normal; // the case's grains' c-axes, in this model's order
  b = std::move(stored);
  std::vector<std::size_t> bond_map(n);
  for (std::size_t k = 0; k < n; ++k)
    bond_map[order[k]] = k;
  return bond_map;
}

void visit_cracks(StateArchive& a, std::vector<CrackEvent>& cracks,
                  const std::vector<std::size_t>& bond_map)
{
  StateGroup group(a, "cracks");
  const std::size_t n = cracks.size();
  std::vector<double> time(n), energy(n);
  std::vector<std::int64_t> bond(n);
  std::vector<std::int32_t> pa(n), pb(n);
  std::vector<Vec3> midpoint(n), axis(n);
  std::vector<CrackMode> mode(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto& c = cracks[k];
    time[k] = c.time, energy[k] = c.energy, bond[k] = std::int64_t(c.bond);
    pa[k] = c.a, pb[k] = c.b, midpoint[k] = c.midpoint, axis[k] = c.axis, mode[k] = c.mode;
  }
  a.io("time", time);
  a.io("bond", bond);
  a.io("a", pa);
  a.io("b", pb);
  a.io("midpoint", midpoint);
  a.io("axis", axis);
  a.io_enums("mode", mode);
  a.io("energy", energy);
  if (!a.loading())
    return;
  const std::size_t m = time.size();
  for (std::size_t size : {bond.size(), pa.size(), pb.size(), midpoint.size(), axis.size(),
                           mode.size(), energy.size()})
    if (size != m)
      throw InputError(a.where() + ": the crack arrays differ in length");
  cracks.resize(m);
  for (std::size_t k = 0; k < m; ++k)
  {
    if (bond[k] < 0 || std::size_t(bond[k]) >= bond_map.size())
      throw InputError(a.where() + "bond: index " + std::to_string(bond[k]) +
                       " outside the model's bonds");
    cracks[k] = {
        time[k],  bond_map[std::size_t(bond[k])], pa[k], pb[k], midpoint[k], axis[k], mode[k],
        energy[k]};
  }
}
} // namespace dembridge::dem
