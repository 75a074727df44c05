#pragma once
// A bond as it travels between MPI ranks: the global ids of its two particles (their index in
// the whole model), the bond's global id (its index in the model's bonds at the setup, which
// the ParaView bond files show) and class, and every per-bond array of the BondStore: the
// constants (rest length and axis, stiffnesses, contact point, radius, dashpots, model), the
// state, and with a failure law the strengths and the damage history. Records are plain doubles
// (ids, enums and state are small integers, exact in a double), so that a rank sends a
// particle's bonds as one array when the particle moves to another rank, and the receiving rank
// appends them to its store as they were, bit for bit. The per-bond force records (a static
// run's) do not travel: distributed runs are explicit and keep none.
#include "dem/bonds/bond_store.h"
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace dembridge::distributed
{
/// Doubles in one record of a bond of @p b (more with a failure law).
std::size_t bond_record_size(const dem::BondStore& b);

/// Writes bond k of @p b, whose particles have the global ids @p ga and @p gb and which is
/// bond @p id of the model, at @p out.
void pack_bond(const dem::BondStore& b, std::size_t k, std::int64_t ga, std::int64_t gb,
               std::int64_t id, double* out);

/// The global ids of the particles of a packed bond (a, b), and of the bond.
inline std::int64_t record_a(const double* record)
{
  return std::int64_t(record[0]);
}
inline std::int64_t record_b(const double* record)
{
  return std::int64_t(record[1]);
}
inline std::int64_t record_id(const double* record)
{
  return std::int64_t(record[2]);
}
/// Whether a packed bond still joins its particles (intact or softening).
bool record_bonded(const double* record);

/// Appends a packed bond to @p b between its local particles @p a and @p b_local (its class
/// too where the model's bonds have classes).
void unpack_bond(const double* record, dem::BondStore& b, std::int32_t a, std::int32_t b_local);

/// A bond's key in a rank's store: its two local particle indices.
inline std::uint64_t local_pair(std::int32_t a, std::int32_t b)
{
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

/// The bonds a rank holds, from the records it has at a rebuild (its own and those sent to it).
struct HeldBonds
{
  /// One copy of each record with an owned end and both ends here, between local indices, in
  /// the bond loop's order (by lower particle: runs of bonds share it, then upper).
  dem::BondStore bonds;
  /// (local_pair, the bond's id) of each, sorted.
  std::vector<std::pair<std::uint64_t, std::int64_t>> ids;
  /// The records of the broken bonds whose end a is owned and end b is not here, one copy each
  /// in the order of their ids.
  std::vector<double> detached;
  /// A bonded pair with an owned end and the other end not here ("ga and gb"), else empty.
  std::string too_long;
};
/// @p local: the local index of each global particle id here; @p n_owned: the owned ones are
/// [0, n_owned); @p failure: the store's failure law.
HeldBonds hold_bonds(const std::vector<double>& records, const dem::FailureLaw& failure,
                     const std::unordered_map<std::int64_t, std::int32_t>& local,
                     std::size_t n_owned);
} // namespace dembridge::distributed
