#include "dem/solvers/time_step.h"
#include "dem/bonds/bond_matrix.h"
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace dembridge::dem
{
TimeStepEstimate estimate_critical_time_step(const ParticleStore& p, const BondStore& bonds,
                                             double gamma)
{
  TimeStepEstimate est;
  double dt_min = std::numeric_limits<double>::infinity(),
         eq48 = std::numeric_limits<double>::infinity();
  // Regular packings repeat a few bond signatures: cache eigenvalues per signature.
  std::map<std::array<double, 12>, double> cache;
  for (std::size_t k = 0; k < bonds.size(); ++k)
  {
    if (!is_bonded(bonds.state[k])) // a softening bond is no stiffer than intact: kept
      continue;
    const int a = bonds.a[k], b = bonds.b[k];
    eq48 = std::min(eq48, 0.22 * std::sqrt(std::min(p.mass[a], p.mass[b]) / bonds.kn[k]));
    const double ca = std::max(1, p.coordination[a]), cb = std::max(1, p.coordination[b]);
    std::array<double, 12> key = {bonds.kn[k],
                                        bonds.ks[k],
                                        bonds.ktor[k],
                                        bonds.kben[k],
                                        bonds.contact_fraction[k],
                                        bonds.rest_length[k],
                                        p.mass[a] / ca,
                                        p.inertia[a] / ca,
                                        p.mass[b] / cb,
                                        p.inertia[b] / cb,
                                        bonds.damping_force[k],
                                        bonds.damping_moment[k]};
    if (bonds.is_smooth_joint(k))
    {
      // a smooth joint's D = k_n n n^T + k_s (I - n n^T) on the contact point's displacement
      // (bond_matrix.h) is at most max(k_n, k_s) I, with no rotational stiffness: that bound
      key[0] = key[1] = std::max(key[0], key[1]);
      key[2] = key[3] = 0;
    }
    auto it = cache.find(key);
    double dt_k;
    if (it != cache.end())
      dt_k = it->second;
    else
    {
      Vector12 minv_sqrt;
      for (int d = 0; d < 3; ++d)
      {
        minv_sqrt[d] = 1.0 / std::sqrt(key[6]);
        minv_sqrt[3 + d] = 1.0 / std::sqrt(key[7]);
        minv_sqrt[6 + d] = 1.0 / std::sqrt(key[8]);
        minv_sqrt[9 + d] = 1.0 / std::sqrt(key[9]);
      }
      // largest eigenvalue of M_e^-1/2 X M_e^-1/2 for the bond's stiffness (X = K) or dashpot
      // (X = C: the same law with the dashpot coefficients in place of the stiffnesses)
      auto largest = [&](double kn, double ks, double ktor, double kben)
      {
        BondStiffness s;
        s.kn = kn, s.ks = ks, s.ktor = ktor, s.kben = kben, s.contact_fraction = key[4];
        const Matrix12 A =
            minv_sqrt.asDiagonal() * unified_bond_matrix(s, key[5]) * minv_sqrt.asDiagonal();
        return Eigen::SelfAdjointEigenSolver<Matrix12>(A, Eigen::EigenvaluesOnly)
            .eigenvalues()
            .maxCoeff();
      };
      const double lam = largest(key[0], key[1], key[2], key[3]);    // omega_max^2
      const double mu = largest(key[10], key[10], key[11], key[11]); // 2 zeta omega, largest
      // central differences with the damping force from v^{n-1/2} are stable for
      // omega^2 dt^2 + 2 mu dt <= 4 (1-DOF analysis; taking both maxima is conservative)
      dt_k = lam > 0 ? (-mu + std::sqrt(mu * mu + 4.0 * lam)) / lam
                     : std::numeric_limits<double>::infinity();
      cache.emplace(key, dt_k);
    }
    dt_min = std::min(dt_min, dt_k);
  }
  est.thesis_eq48 = eq48;
  est.bond_bound = dt_min / std::sqrt(1.0 + gamma);
  return est;
}
} // namespace dembridge::dem
