#include "coupling/packing_strength.h"
#include "dem/bonds/bond_stress.h"
#include <algorithm>
#include <cmath>

namespace dembridge::coupling
{
std::vector<BondFamily> bond_families(const std::vector<Vec3>& rest_axes,
                                      const std::vector<double>& rest_lengths,
                                      const std::vector<double>& radii_a,
                                      const std::vector<double>& radii_b,
                                      const dem::BondMaterial& material)
{
  std::vector<BondFamily> families;
  for (std::size_t k = 0; k < rest_axes.size(); ++k)
  {
    Vec3 n = rest_axes[k].normalized();
    // one sign per direction: the first component that is not zero positive
    for (int d = 0; d < 3; ++d)
      if (std::abs(n[d]) > 1e-9)
      {
        if (n[d] < 0)
          n = -n;
        break;
      }
    const bool known = std::any_of(families.begin(), families.end(),
                                   [&](const BondFamily& f) { return (f.axis - n).norm() < 1e-6; });
    if (known)
      continue;
    const auto k0 = dem::bond_stiffness(material, rest_lengths[k], radii_a[k], radii_b[k]);
    families.push_back({n, k0.kn, k0.ks, rest_lengths[k], k0.radius});
  }
  return families;
}

double utilisation(const PackingStrength& s, const Eigen::Matrix3d& strain)
{
  double largest = 0;
  for (const auto& f : s.families)
  {
    const Vec3 stretch = strain * f.axis;
    const double normal = f.axis.dot(stretch);
    const Vec3 offset = stretch - normal * f.axis;
    // the contact force on b (bond_kernel.h: F = k_n delta_n e + k_s delta_s)
    const Vec3 F = -f.kn * f.rest_length * normal * f.axis + f.ks * f.rest_length * offset;
    const Vec3 M = Vec3::Zero();
    const auto stress =
        dem::bond_stress(F.data(), M.data(), f.axis.data(), f.radius, s.law.moment_factor);
    const double tau_max =
        dem::shear_strength(s.law, s.shear_strength, stress.normal_force, stress.area);
    largest = std::max({largest, stress.tensile / s.tensile_strength, stress.shear / tau_max});
  }
  return largest;
}
} // namespace dembridge::coupling
