#include "dem/bonds/bonding.h"
#include "dem/packing/cell_list.h"
#include <algorithm>
#include <cmath>

namespace dembridge::dem
{
void add_bond(ParticleStore& p, BondStore& bonds, const BondMaterial& mat, int i, int j)
{
  const int n = int(p.size());
  if (i < 0 || j < 0 || i >= n || j >= n || i == j)
    throw InputError("bond (" + std::to_string(i) + ", " + std::to_string(j) +
                     ") does not join two distinct existing particles (there are " +
                     std::to_string(n) + ")");
  if (i > j)
    std::swap(i, j); // order by index so results do not depend on input order
  const Vec3 d = p.position[j] - p.position[i];
  const double L = d.norm();
  if (!(L > 1e-12 * (p.radius[i] + p.radius[j])))
    throw InputError("particles " + std::to_string(i) + " and " + std::to_string(j) +
                     " sit at the same position: a bond needs a length");
  const BondStiffness k = bond_stiffness(mat, L, p.radius[i], p.radius[j]);
  bonds.add(i, j, L, d / L, mat.model, k);
  ++p.coordination[i];
  ++p.coordination[j];
}

std::size_t form_bonds(ParticleStore& p, BondStore& bonds, const BondMaterial& mat, double eta)
{
  if (!(eta > 0))
    throw InputError("Bonds/contact radius multiplier: must be positive");
  const std::size_t before = bonds.size();
  if (p.size() < 2)
    return 0;
  const double rmax = *std::max_element(p.radius.begin(), p.radius.end());
  const double reach = 2.0 * eta * rmax * (1.0 + 1e-9);
  CellList cells(p.position, reach);
  std::vector<std::pair<int, int>> pairs;
  cells.for_each_pair(p.position,
                      [&](int i, int j)
                      {
                        const double lim = eta * (p.radius[i] + p.radius[j]) * (1.0 + 1e-9);
                        if ((p.position[j] - p.position[i]).squaredNorm() <= lim * lim)
                          pairs.emplace_back(std::min(i, j), std::max(i, j));
                      });
  std::sort(pairs.begin(), pairs.end()); // deterministic bond order
  bonds.reserve(bonds.size() + pairs.size());
  for (auto [i, j] : pairs)
    add_bond(p, bonds, mat, i, j);
  mark_reference_configuration(p);
  return bonds.size() - before;
}

void mark_reference_configuration(ParticleStore& p)
{
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    p.orientation[i] = Quat::Identity();
    p.reference_position[i] = p.position[i];
  }
}

void assign_bond_damping(const ParticleStore& p, BondStore& bonds, double xi)
{
  for (std::size_t k = 0; k < bonds.size(); ++k)
  {
    const int i = bonds.a[k], j = bonds.b[k];
    const double mred = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
    const double ired = p.inertia[i] * p.inertia[j] / (p.inertia[i] + p.inertia[j]);
    const double C = 0.5 * (p.coordination[i] + p.coordination[j]);
    const double scale = 1.0 / std::sqrt(std::max(C, 1.0) / 3.0);              // eq. 37
    bonds.damping_force[k] = xi * 2.0 * std::sqrt(bonds.kn[k] * mred) * scale; // eq. 36
    bonds.damping_moment[k] =
        xi * 2.0 * std::sqrt(2.0 * bonds.ktor[k] * ired) * scale; // paper eq. 10
  }
}
} // namespace dembridge::dem
