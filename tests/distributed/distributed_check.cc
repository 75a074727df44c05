// Checks of the distributed particle layer (distributed/), run under mpirun on 1, 2 and 3 ranks:
//   distributed_check flying_cluster
//   distributed_check repartitioned_cluster
//   distributed_check breaking_bar
//   distributed_check shattering_cluster
//   distributed_check colliding_clusters
// each case in its own file (flying_cluster_check.cc for the first two, then
// breaking_bar_check.cc, shattering_cluster_check.cc, colliding_clusters_check.cc), which says
// what it checks against the same model stepped on one rank.
// Exit code 0 on success; a failed check prints one line on rank 0 and returns 1.
#include "distributed_check.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>

using namespace dembridge::distributed_check;

namespace dembridge::distributed_check
{
void check(bool ok, const std::string& what)
{
  if (!ok)
  {
    ++failures;
    if (root)
      std::cout << "FAILED: " << what << std::endl;
  }
  else if (root)
    std::cout << "ok: " << what << std::endl;
}

std::string figure(double x)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

double energy_difference(const dem::EnergyBalance& ranks, const dem::EnergyBalance& one)
{
  const auto& e = ranks;
  const auto& s = one;
  double worst = 0;
  for (const auto& [x, y] :
       {std::pair(e.kinetic, s.kinetic), std::pair(e.strain, s.strain),
        std::pair(e.damping, s.damping), std::pair(e.external, s.external),
        std::pair(e.fracture, s.fracture), std::pair(e.contact_strain, s.contact_strain),
        std::pair(e.friction, s.friction), std::pair(e.contact_damping, s.contact_damping),
        std::pair(e.wall_work, s.wall_work), std::pair(e.initial, s.initial)})
    worst = std::max(worst, std::abs(x - y));
  return worst / s.largest();
}

std::string relative(double a, double b)
{
  return figure(std::abs(a - b) / std::max(std::abs(b), 1e-300));
}
} // namespace dembridge::distributed_check

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const std::string name = argc > 1 ? argv[1] : "";
  try
  {
    if (name == "flying_cluster")
      return flying_cluster_check(MPI_COMM_WORLD, 5e-3, 4000, false);
    if (name == "repartitioned_cluster")
      return flying_cluster_check(MPI_COMM_WORLD, 2.5e-3, 2000, true);
    if (name == "breaking_bar")
      return breaking_bar_check(MPI_COMM_WORLD);
    if (name == "colliding_clusters")
      return colliding_clusters_check(MPI_COMM_WORLD);
    if (name == "shattering_cluster")
      return shattering_cluster_check(MPI_COMM_WORLD);
    if (root)
      std::cerr << "usage: distributed_check flying_cluster | repartitioned_cluster | breaking_bar "
                   "| colliding_clusters | "
                   "shattering_cluster"
                << std::endl;
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "distributed_check: " << e.what() << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  return 1;
}
