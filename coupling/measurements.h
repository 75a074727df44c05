#pragma once
// Measurements on a coupled run: the longitudinal pulse of the reflection tests, the uniform
// strain of the particle region, the regional energies.
//
// Pulse (a Gaussian-windowed cosine, the "dominant wavelength" lambda):
//   f(s) = A exp(-(s / (e lambda))^2) cos(2 pi s / lambda),   s = X_axis - x_0   (m)
// travelling in direction d = +-1 along the axis with the phase speed c_h of the grid it starts
// on. Central differences carry a grid wave exactly when it moves at the fully discrete phase
// speed of a chain of spacing h (lumped Q1 elements and the simple cubic lattice along an axis
// are such chains for a plane longitudinal wave):
//   sin(omega dt / 2) = (c dt / h) sin(k h / 2),   c_h = omega / k                     (1)
// so the initial state is u_0(X) = f(s) e_axis and, in the leapfrog convention v^{-1/2} =
// (u^0 - u^{-1}) / dt, v^{-1/2}(X) = (f(s) - f(s + d c_h dt)) / dt e_axis: a discrete wave with
// almost no part running the other way.
#include "coupling/handshake.h"
#include "dem/core/particle_store.h"
#include <array>
#include <functional>

namespace dembridge::coupling
{
struct Pulse
{
  int axis = 0;
  double centre = 0;     ///< x_0, m
  double wavelength = 0; ///< lambda, m
  double envelope = 1;   ///< e: Gaussian width in wavelengths
  double amplitude = 1e-6;
  int direction = 1; ///< +1 or -1 along the axis
  double speed = 0;  ///< c_h, m/s (eq. 1)
};

/// Eq. (1): phase speed of central differences on a chain of spacing h (m) for the long-wave
/// speed c (m/s), time step dt (s) and wavelength lambda (m).
double discrete_phase_speed(double c, double h, double dt, double wavelength);

Vec3 pulse_displacement(const Pulse& pulse, const Vec3& X);
/// v^{-1/2}(X) for the time step dt (see the file comment).
Vec3 pulse_velocity(const Pulse& pulse, const Vec3& X, double dt);

/// Least-squares affine fit u(X) = u_0 + E X of the particle displacements selected by
/// @p select (rank 0's particles); returns the symmetric part of E (the strain), row-major 3x3.
std::array<double, 9> fit_particle_strain(const dem::ParticleStore& p,
                                          const std::function<bool(const Vec3&)>& select);
} // namespace dembridge::coupling
