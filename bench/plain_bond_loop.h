#pragma once
// The machine's reference bond loop for dembridge-bench: a plain structure-of-arrays
// parallel-bond loop as in PFC's linear parallel bond (Potyondy & Cundall 2004, eq. 5-8), in
// incremental form, with a dashpot and velocity Verlet; no quaternions, no energy booking.
//
// Per bond (a, b), contact point x_c = x_a + s d, d = x_b - x_a, n = d / |d|:
//   v_c = (v_b + w_b x (x_c - x_b)) - (v_a + w_a x (x_c - x_a))   velocity of b relative to a
//   w_r = w_b - w_a
//   F_n += -k_n (v_c . n) dt                 normal force on b (scalar along n)
//   F_s  = F_s - (F_s . n) n - k_s (v_c - (v_c . n) n) dt    (shear, kept in the plane)
//   M_t += -k_t (w_r . n) dt
//   M_b  = M_b - (M_b . n) n - k_b (w_r - (w_r . n) n) dt
//   F = F_n n + F_s - c_t v_c,  M = M_t n + M_b - c_r w_r      on b; -F, -M on a
//   M_a += (x_c - x_a) x (-F),  M_b += (x_c - x_b) x F
// Then v += dt F / m, w += dt M / I, x += dt v (central differences).
// It has the same particles, bonds, bond order and thread partition as the full model, so the
// ratio of the two is the cost of the full law (total co-rotational form, quaternions, exact
// energy booking) on the same memory traffic.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/solvers/bond_partition.h"

namespace dembridge::bench
{
class PlainBondLoop
{
public:
  /// Copies the particles' state and the bonds' stiffnesses; @p partition as the solver's.
  PlainBondLoop(const dem::ParticleStore& p, const dem::BondStore& b, double dt, int threads);
  void step();
  /// Bytes the loop holds (capacity of its arrays).
  std::size_t memory_bytes() const;
  /// Largest particle speed (m/s): the loop stays stable at the full model's time step.
  double max_speed() const;

private:
  void bond_range(std::size_t begin, std::size_t end);
  int threads_;
  double dt_;
  std::size_t n_;
  // particles
  std::vector<dem::Vec3> x_, v_, w_, F_, M_;
  std::vector<double> inv_m_, inv_I_;
  // bonds: constants and incremental state
  std::vector<std::int32_t> a_, b_;
  std::vector<double> kn_, ks_, kt_, kb_, s_, ct_, cr_;
  std::vector<double> fn_, mt_;
  std::vector<dem::Vec3> fs_, mb_;
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> phases_;
};
} // namespace dembridge::bench
