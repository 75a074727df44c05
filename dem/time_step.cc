#include "time_step.h"
#include "bond_matrix.h"
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace dembridge::dem
{
TimeStepEstimate estimate_critical_time_step(const ParticleStore& p, const BondStore& bonds,
                                             double xi, double gamma)
{
  TimeStepEstimate est;
  double dt_min = std::numeric_limits<double>::infinity(),
         eq48 = std::numeric_limits<double>::infinity();
  // Regular packings repeat a few bond signatures: cache eigenvalues per signature.
  std::map<std::array<double, 10>, double> cache;
  for (std::size_t k = 0; k < bonds.size(); ++k)
  {
    if (bonds.state[k] != BondState::intact)
      continue;
    const int a = bonds.a[k], b = bonds.b[k];
    eq48 = std::min(eq48, 0.22 * std::sqrt(std::min(p.mass[a], p.mass[b]) / bonds.kn[k]));
    const double ca = std::max(1, p.coordination[a]), cb = std::max(1, p.coordination[b]);
    const std::array<double, 10> key = {bonds.kn[k],
                                        bonds.ks[k],
                                        bonds.ktor[k],
                                        bonds.kben[k],
                                        bonds.contact_fraction[k],
                                        bonds.rest_length[k],
                                        p.mass[a] / ca,
                                        p.inertia[a] / ca,
                                        p.mass[b] / cb,
                                        p.inertia[b] / cb};
    auto it = cache.find(key);
    double lam;
    if (it != cache.end())
      lam = it->second;
    else
    {
      BondStiffness s;
      s.kn = key[0], s.ks = key[1], s.ktor = key[2], s.kben = key[3], s.contact_fraction = key[4];
      const Matrix12 K = unified_bond_matrix(s, key[5]);
      Vector12 minv_sqrt;
      for (int d = 0; d < 3; ++d)
      {
        minv_sqrt[d] = 1.0 / std::sqrt(key[6]);
        minv_sqrt[3 + d] = 1.0 / std::sqrt(key[7]);
        minv_sqrt[6 + d] = 1.0 / std::sqrt(key[8]);
        minv_sqrt[9 + d] = 1.0 / std::sqrt(key[9]);
      }
      const Matrix12 A = minv_sqrt.asDiagonal() * K * minv_sqrt.asDiagonal();
      Eigen::SelfAdjointEigenSolver<Matrix12> eig(A, Eigen::EigenvaluesOnly);
      lam = eig.eigenvalues().maxCoeff();
      cache.emplace(key, lam);
    }
    // The dashpot ratio of this bond after the coordination scaling of thesis eq. 37.
    const double c_mean = 0.5 * (p.coordination[a] + p.coordination[b]);
    const double xi_k = xi / std::sqrt(std::max(c_mean, 1.0) / 3.0);
    if (lam > 0)
      dt_min = std::min(dt_min, 2.0 / std::sqrt(lam) * (std::sqrt(1.0 + xi_k * xi_k) - xi_k));
  }
  est.thesis_eq48 = eq48;
  est.bond_bound = dt_min / std::sqrt(1.0 + gamma);
  return est;
}
} // namespace dembridge::dem
