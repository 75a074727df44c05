#pragma once
// Particle storage: structure of arrays, one std::vector per field, so that the integrator and
// the bond kernel stream through contiguous memory. Spheres only: the inertia tensor is
// isotropic, I = 2/5 m r^2 (thesis eq. 42).
#include "dem/core/types.h"
#include <vector>

namespace dembridge::dem
{
struct ParticleStore
{
  std::vector<Vec3> position;            // m
  std::vector<Vec3> reference_position;  // m, position when bonds were formed
  std::vector<Vec3> velocity;            // m/s (at the half step t - dt/2 between steps)
  std::vector<Vec3> angular_velocity;    // rad/s (global frame, half step)
  std::vector<Quat> orientation;         // rotation since bond formation
  std::vector<Vec3> force;               // N, resultant of bonds and external loads
  std::vector<Vec3> torque;              // N·m
  std::vector<double> radius;            // m
  std::vector<double> mass;              // kg
  std::vector<double> inertia;           // kg·m^2 (scalar: spheres)
  std::vector<std::uint8_t> dof_mask;    // DofBit: constrained DOFs (fixed or prescribed); the
                                         // prescribed values live in the solver (few particles)
  std::vector<std::uint32_t> group_mask; // bit g set: particle belongs to group g
  std::vector<int> coordination;         // number of intact bonds
  /// The particle's id as the user numbers it (its index as generated or read): the stores are
  /// renumbered into spatial order at setup (dem/model/renumbering.h); outputs show this id.
  std::vector<std::int32_t> id;
  /// The grain each particle belongs to (dem/microstructure/columnar_grains.h); empty without
  /// grains.
  std::vector<std::int32_t> grain;

  std::size_t size() const { return position.size(); }

  /// Appends a sphere of radius r (m) and density rho (kg/m^3) at rest.
  void add(const Vec3& x, double r, double rho);

  /// Sets the mass of particle i (kg) and the matching sphere inertia.
  void set_mass(std::size_t i, double m);

  /// Bytes the store holds (the capacity of every array).
  std::size_t memory_bytes() const;
};
} // namespace dembridge::dem
