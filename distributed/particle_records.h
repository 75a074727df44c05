#pragma once
// A particle as it travels to a new owner rank (a migration or a repartition): its global id,
// ParticleStore's fields but the position (the handler's location carries it) and its support
// reaction, as plain doubles (ids, masks and counts are small integers, exact in a double), the
// counterpart of bond_records.h for its bonds.
#include "dem/core/particle_store.h"
#include "distributed/distributed_particles.h"
#include <cstddef>
#include <cstdint>

namespace dembridge::distributed
{
/// A particle's state as it travels to a new owner: its global id, ParticleStore's fields but
/// the position (the handler's location) and its support reaction (33 doubles).
namespace state
{
constexpr unsigned id = 0, reference_position = 1, velocity = 4, angular_velocity = 7,
                   orientation = 10, force = 14, torque = 17, radius = 20, mass = 21, inertia = 22,
                   dof_mask = 23, group_mask = 24, coordination = 25, user_id = 26, reaction = 27,
                   count = 33;
}

/// Writes particle i of @p p, of global id @p id, with its group mask and reaction, at @p out
/// (state::count doubles).
void pack_state(const dem::ParticleStore& p, std::size_t i, std::int64_t id,
                std::uint32_t group_mask, const Reaction& reaction, double* out);

/// Fills entry i of @p p (all but its position) from a packed state; returns the reaction.
Reaction unpack_state(const double* in, dem::ParticleStore& p, std::size_t i);

/// Resizes every per-particle array of @p p to @p n.
void resize(dem::ParticleStore& p, std::size_t n);
} // namespace dembridge::distributed
