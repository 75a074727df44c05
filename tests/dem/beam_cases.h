#pragma once
// Beam verification cases of the seeds, as CaseConfigs, and their analytical solutions.
//  - Thesis Appendix B: simply supported Timoshenko beam, central load (eq. B1), and the free
//    vibration of a three-particle beam (eq. B2-B3).
//  - Chen et al. (2022) section 3: cantilever with a tip load (eq. 29), cases 1, 3 and 5.
#include "dem/model/case_config.h"
#include <cmath>
#include <numbers>

namespace dembridge::test
{
using namespace dembridge::dem;

inline double area(double r)
{
  return std::numbers::pi * r * r;
}
inline double second_moment(double r)
{
  return 0.25 * std::numbers::pi * std::pow(r, 4);
}
inline double shear_modulus(double E, double nu)
{
  return E / (2.0 * (1.0 + nu));
}
constexpr double form_factor_circle = 10.0 / 9.0;

/// Thesis eq. B1: midspan deflection of a simply supported Timoshenko beam, central load F.
inline double simply_supported_deflection(double F, double Le, double E, double nu, double r)
{
  return F * std::pow(Le, 3) / (48 * E * second_moment(r)) +
         F * Le * form_factor_circle / (4 * shear_modulus(E, nu) * area(r));
}

/// Thesis eq. B2-B3: natural frequency (Hz) of a central mass m on a simply supported beam.
inline double simply_supported_frequency(double m, double Le, double E, double nu, double r)
{
  const double EI = E * second_moment(r), GA = shear_modulus(E, nu) * area(r);
  const double K = 192 * EI * GA / (4 * std::pow(Le, 3) * GA + 48 * form_factor_circle * EI * Le);
  return std::sqrt(K / m) / (2 * std::numbers::pi);
}

/// Paper eq. 29 (Timoshenko) and its first term (Euler–Bernoulli): cantilever tip deflection.
inline double cantilever_timoshenko(double F, double L, double E, double nu, double r)
{
  return F * std::pow(L, 3) / (3 * E * second_moment(r)) +
         10 * F * L / (9 * shear_modulus(E, nu) * area(r));
}
inline double cantilever_euler_bernoulli(double F, double L, double E, double r)
{
  return F * std::pow(L, 3) / (3 * E * second_moment(r));
}

/// Thesis Appendix B beam: n particles of radius 0.1 m touching along x, E_b = 4 GPa,
/// nu_b = 0.3, TBBM, 1 kN central load in -z, pin (left) and roller (right) supports.
inline CaseConfig simply_supported_beam(int n)
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::row;
  c.particles.count = n;
  c.particles.radius = 0.1;
  c.particles.density = 2500;
  c.bonds.material.model = BondModel::timoshenko;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  GroupConfig left{"left", {}, 0, 0, Vec3::Zero()}, right = left, mid = left;
  left.selection.kind = right.selection.kind = mid.selection.kind = GroupSelection::Kind::index;
  left.selection.indices = {0};
  left.fixed = dof_ux | dof_uy | dof_uz | dof_rx | dof_rz; // rotation about y free
  right.name = "right";
  right.selection.indices = {-1};
  right.fixed = dof_uy | dof_uz | dof_rx | dof_rz; // slides along x
  mid.name = "midspan";
  mid.selection.indices = {n / 2};
  c.groups = {left, right, mid};
  LoadConfig load;
  load.group = "midspan";
  load.load.name = "point_load";
  load.load.kind = LoadKind::force;
  load.load.value = Vec3(0, 0, -1000);
  load.load.ramp_time = 0.5;
  c.loads = {load};
  c.run.particle_damping = 0.7;
  c.run.end_time = 100;
  c.run.quasi_static_speed = 1e-9;
  c.measure.deflection_group = "midspan";
  c.measure.deflection_name = "midspan_deflection";
  return c;
}

/// Thesis Appendix B free vibration: three particles, L_e = 0.4 m, central mass 7.4 kg, end
/// particles 1e-4 of it; the centre starts with -1 m/s in z.
inline CaseConfig free_vibration_beam()
{
  CaseConfig c = simply_supported_beam(3);
  c.loads.clear();
  c.groups[0].mass = c.groups[1].mass = 7.4e-4;
  c.groups[2].mass = 7.4;
  c.groups[2].initial_velocity = Vec3(0, 0, -1);
  c.run.particle_damping = 0;
  c.run.quasi_static_speed = 0;
  c.run.end_time = 0.0105; // about 7.5 periods
  c.measure.frequency_group = "midspan";
  return c;
}

/// Paper case 1 family: cantilever of `bonds` bonds over `length` (m), bond radius 0.2 m,
/// E_b = 200 GPa, nu_b = 0.3, 100 kN tip load ramped over 1 s (paper section 3), particle 0
/// clamped. Radii: all 0.2 m unless `radii` is given.
inline CaseConfig cantilever(BondModel model, int bonds, double length = 4.0,
                             std::vector<double> radii = {})
{
  CaseConfig c;
  c.particles.kind = ParticleSource::Kind::row;
  c.particles.count = bonds + 1;
  c.particles.radius = 0.2;
  c.particles.radii = radii;
  c.particles.spacing = length / bonds;
  c.particles.density = 7850;
  c.bonds.material.model = model;
  c.bonds.material.youngs_modulus = 200e9;
  c.bonds.material.poisson_ratio = 0.3;
  for (int i = 0; i < bonds; ++i)
    c.bonds.explicit_bonds.push_back({i, i + 1});
  GroupConfig fixed{"fixed_end", {}, 63, 0, Vec3::Zero()}, tip{"tip", {}, 0, 0, Vec3::Zero()};
  fixed.selection.kind = tip.selection.kind = GroupSelection::Kind::index;
  fixed.selection.indices = {0};
  tip.selection.indices = {-1};
  c.groups = {fixed, tip};
  LoadConfig load;
  load.group = "tip";
  load.load.name = "tip_load";
  load.load.value = Vec3(0, 0, -1e5);
  load.load.ramp_time = 1.0;
  c.loads = {load};
  c.run.particle_damping = 0.7;
  c.run.end_time = 100;
  c.run.quasi_static_speed = 1e-9;
  c.measure.deflection_group = "tip";
  c.measure.deflection_name = "tip_deflection";
  return c;
}
} // namespace dembridge::test
