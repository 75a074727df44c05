#include "coupling/measurements.h"
#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace dembridge::coupling
{
double discrete_phase_speed(const double c, const double h, const double dt,
                            const double wavelength)
{
  const double k = 2 * std::numbers::pi / wavelength;
  const double s = c * dt / h * std::sin(0.5 * k * h); // eq. (1)
  if (!(s < 1))
    throw std::runtime_error("Coupling/Wave: the time step is above the chain's stability limit");
  return 2 * std::asin(s) / dt / k;
}

namespace
{
double profile(const Pulse& pulse, const double s)
{
  const double width = pulse.envelope * pulse.wavelength;
  return pulse.amplitude * std::exp(-(s / width) * (s / width)) *
         std::cos(2 * std::numbers::pi * s / pulse.wavelength);
}
} // namespace

Vec3 pulse_displacement(const Pulse& pulse, const Vec3& X)
{
  Vec3 u = Vec3::Zero();
  u[pulse.axis] = profile(pulse, X[pulse.axis] - pulse.centre);
  return u;
}

Vec3 pulse_velocity(const Pulse& pulse, const Vec3& X, const double dt)
{
  const double s = X[pulse.axis] - pulse.centre;
  Vec3 v = Vec3::Zero();
  // u^{-1}(X) = f(s + d c dt): the wave one step earlier
  v[pulse.axis] = (profile(pulse, s) - profile(pulse, s + pulse.direction * pulse.speed * dt)) / dt;
  return v;
}

std::array<double, 9> fit_particle_strain(const dem::ParticleStore& p,
                                          const std::function<bool(const Vec3&)>& select)
{
  // u_c = a_c + sum_j E_cj X_j for every selected particle: normal equations of [1 X] per
  // component, coordinates centred for conditioning.
  Vec3 mean = Vec3::Zero();
  long n = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (select(p.reference_position[i]))
      mean += p.reference_position[i], ++n;
  if (n < 4)
    throw std::runtime_error("fit_particle_strain: fewer than four particles selected");
  mean /= double(n);
  Eigen::Matrix3d XtX = Eigen::Matrix3d::Zero(), XtU = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (select(p.reference_position[i]))
    {
      const Vec3 X = p.reference_position[i] - mean;
      const Vec3 u = p.position[i] - p.reference_position[i];
      XtX += X * X.transpose();
      XtU += X * u.transpose();
    }
  // A lattice one particle thick along an axis has no information there: fit only the axes
  // with extent (the strain along the others is left at zero).
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  std::vector<int> axes;
  for (int d = 0; d < 3; ++d)
    if (XtX(d, d) > 1e-12 * XtX.trace())
      axes.push_back(d);
  Eigen::MatrixXd A(axes.size(), axes.size()), B(axes.size(), 3);
  for (std::size_t a = 0; a < axes.size(); ++a)
  {
    for (std::size_t b = 0; b < axes.size(); ++b)
      A(a, b) = XtX(axes[a], axes[b]);
    B.row(a) = XtU.row(axes[a]);
  }
  const Eigen::MatrixXd G = A.ldlt().solve(B); // G(a, c) = d u_c / d X_axes[a]
  for (std::size_t a = 0; a < axes.size(); ++a)
    for (int c = 0; c < 3; ++c)
      E(c, axes[a]) = G(a, c);
  const Eigen::Matrix3d eps = 0.5 * (E + E.transpose());
  std::array<double, 9> out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[3 * r + c] = eps(r, c);
  return out;
}
} // namespace dembridge::coupling
