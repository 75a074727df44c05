#pragma once
// The checks of distributed_check (distributed_check.cc), one file a case, and what they share:
// the count of failed checks, whether this is rank 0 (which prints), and the printed figures.
#include "dem/core/energy.h"
#include <deal.II/base/mpi.h>
#include <string>

namespace dembridge::distributed_check
{
/// Failed checks on this rank.
inline int failures = 0;
/// Whether this is rank 0, which prints each check's line.
inline bool root = false;

/// Prints "ok: @p what" or "FAILED: @p what" (rank 0) and counts a failure.
void check(bool ok, const std::string& what);
/// @p x with 3 digits.
std::string figure(double x);
/// |a - b| / |b| with 3 digits.
std::string relative(double a, double b);
/// The largest difference between any term of @p ranks and of @p one (every term of the balance,
/// kinetic to the walls' work and the initial energy), relative to @p one's largest term.
double energy_difference(const dem::EnergyBalance& ranks, const dem::EnergyBalance& one);

/// The cases (flying_cluster_check.cc, ...): each returns 0 when every check passed on every
/// rank, 1 otherwise; @p radius, @p steps, @p balanced: see flying_cluster_check.cc.
int flying_cluster_check(MPI_Comm comm, double radius, long steps, bool balanced);
int shattering_cluster_check(MPI_Comm comm);
int breaking_bar_check(MPI_Comm comm);
int colliding_clusters_check(MPI_Comm comm);
} // namespace dembridge::distributed_check
