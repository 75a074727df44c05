#pragma once
// What a contact case measures (Chung & Ooi 2011 benchmarks): the largest overlap and normal
// force of any contact over the run, and for the first contact that closes and opens again its
// duration and restitution coefficient
//   e = (separating normal speed after) / (approaching normal speed before),
// from the centres' relative velocity (for a wall: relative to the wall). The contact's start
// and end times are interpolated linearly between the steps where the overlap changes sign, so
// the duration is not quantised to the time step.
#include <cstdint>

namespace dembridge::dem
{
struct ContactMonitor
{
  bool enabled = false;
  double max_overlap = 0; ///< m
  double max_force = 0;   ///< largest normal force, N

  // the first contact
  bool started = false, finished = false;
  bool wall = false; ///< a sphere-wall contact (a = wall index, b = particle)
  std::int32_t a = -1, b = -1;
  double start_time = 0, end_time = 0;          ///< s
  double approach_speed = 0, rebound_speed = 0; ///< m/s
  double last_overlap = 0;

  double duration() const { return finished ? end_time - start_time : 0.0; }
  double restitution() const
  {
    return finished && approach_speed > 0 ? rebound_speed / approach_speed : 0.0;
  }
};
} // namespace dembridge::dem

namespace dembridge::dem
{
/// A uniaxial test between two walls (platens) facing each other: the stress is the mean force
/// with which the particles press on the platens over the specimen's cross-section A, the strain
/// the platens' approach over their initial distance L_0 (compression positive):
///   sigma = (F_lower + F_upper) / (2 A),   F = -(force on the wall) . n  (n into the specimen)
///   eps   = (u_lower . n_lower + u_upper . n_upper) / L_0
/// evaluated every step, so the peak is not sampled at the history interval.
struct PlatenTest
{
  bool enabled = false;
  int lower = -1, upper = -1;    ///< wall indices
  double area = 0;               ///< m^2
  double length = 0;             ///< L_0, m
  double stress = 0, strain = 0; ///< at the last step, Pa and 1
  double peak_stress = 0, strain_at_peak = 0, time_at_peak = 0;
};
} // namespace dembridge::dem
