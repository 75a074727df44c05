// The contact springs' stability limit (ContactForces::critical_time_step).
#include "dem/contacts/contact_forces.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace dembridge::dem
{
// Stability limit of the contact springs, by the element eigenvalue inequality (as the bonds',
// time_step.h): lambda_max(M^-1 K) <= max over contacts of lambda_max(M_e^-1 K_e), where M_e
// gives each body the share m_i / n_i of its mass (and inertia) if it carries n_i contacts. A
// spring k between spheres i, j then has omega^2 = k (n_i/m_i + n_j/m_j); a tangential spring at
// the surface also turns both spheres (compliance 1/m + R^2/I each), a rolling spring only turns
// them (1/I each); a wall contact has the sphere alone. The contacts a sphere will carry are not
// known at setup (a dense packing gives some spheres 8-10, a single impact 1), so n_i is the most
// that fit: the spheres of the smallest radius r that can touch sphere i without overlapping each
// other, at most 2 / (1 - cos theta) with sin theta = r / (R_i + r) (their caps on a sphere around
// i do not overlap; 12 for equal spheres, the kissing number), plus one per wall up to three (a
// box corner). Every pair is bounded by its more compliant partner twice. Central differences
// with the dashpot from v^{n-1/2} are stable for dt <= 2/omega (sqrt(1 + zeta^2) - zeta)
// (time_step.h).
//   linear: the given k_n, k_t; k_r from k_n;
//   Hertz-Mindlin: the stiffnesses grow with the overlap, evaluated at a reference overlap of
//   5 % of R* (beyond it an impact has left Hertz's small-strain theory), and not above the
//   Rayleigh step pi R sqrt(rho/G) / (0.1631 nu + 0.8766) that EDEM recommends.
double ContactForces::critical_time_step(const ParticleStore& p) const
{
  constexpr double reference_overlap = 0.05;
  double dt = std::numeric_limits<double>::infinity();
  const bool hertz = material_.model == ContactModel::hertz_mindlin;
  const double zeta =
      hertz ? std::sqrt(5.0 / 6.0) * std::abs(hertz_pair_.beta) : material_.damping_ratio();
  const double damping_factor = std::sqrt(1.0 + zeta * zeta) - zeta;
  double r_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i)
    r_min = std::min(r_min, p.radius[i]);
  const double wall_contacts = double(std::min<std::size_t>(walls_.size(), 3));
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const double m = p.mass[i], I = p.inertia[i], R = p.radius[i];
    const double tangential_compliance = 1.0 / m + R * R / I;
    const double sin_theta = r_min / (R + r_min);
    const double neighbours =
        R <= r_min ? 12.0 : std::floor(2.0 / (1.0 - std::sqrt(1.0 - sin_theta * sin_theta)) + 1e-9);
    const double n = neighbours + wall_contacts; // contacts sphere i can carry at once
    double omega2 = 0;
    for (int wall = 0; wall < (walls_.empty() ? 1 : 2); ++wall)
    {
      const double share = wall ? n : 2.0 * n; // a pair: both partners as compliant as this one
      const double r_eff = wall ? R : 0.5 * R;
      double kn, kt;
      if (hertz)
      {
        const HertzMindlin& law = wall ? hertz_wall_ : hertz_pair_;
        const auto resp = law(reference_overlap * r_eff, r_eff, m);
        kn = resp.stiffness, kt = resp.kt;
      }
      else
        kn = linear_pair_.kn, kt = linear_pair_.kt;
      omega2 = std::max({omega2, share * kn / m, share * kt * tangential_compliance});
      if (rolling_.friction > 0)
        omega2 = std::max(omega2, share * rolling_.spring(kn, r_eff) / I);
    }
    if (omega2 > 0)
      dt = std::min(dt, 2.0 / std::sqrt(omega2) * damping_factor);
    if (hertz)
    {
      const double rho = m / (4.0 / 3.0 * std::numbers::pi * R * R * R);
      const double nu = material_.poisson_ratio;
      const double G = material_.youngs_modulus / (2.0 * (1.0 + nu));
      dt = std::min(dt, std::numbers::pi * R * std::sqrt(rho / G) / (0.1631 * nu + 0.8766));
    }
  }
  return dt;
}
} // namespace dembridge::dem
