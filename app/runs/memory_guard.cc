#include "app/runs/memory_guard.h"
#include "app/input/dem_parameters.h"
#include "dem/model/size_estimate.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "fem/mesh_estimate.h"
#endif
#ifdef DEMBRIDGE_HAVE_COUPLING
#include "app/input/coupled_parameters.h"
#include "coupling/mesh_estimate.h"
#endif
#include <cstdio>
#include <deal.II/base/mpi.h>
#include <sstream>
#include <sys/resource.h>

namespace dembridge::app
{
namespace
{
/// Meshes from this many cells are announced before they are built: a coupled continuum of
/// 141 k cells took two minutes to set up (coupled_compression.prm, element size 2.5 mm).
constexpr double announced_cells = 1e5;

void announce_mesh(const char* what, double cells, double dofs, double bytes)
{
  if (cells < announced_cells || dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return;
  std::printf("%s: building about %.3g cells and %.3g DoFs (estimated, about %s of memory); this "
              "takes a while\n",
              what, cells, dofs, human_bytes(bytes).c_str());
  std::fflush(stdout);
}
} // namespace

nlohmann::json check_memory(dealii::ParameterHandler& prm)
{
  const std::string mode = prm.get("Mode");
  const double available = available_memory_bytes();
  nlohmann::json j = {{"available_bytes", available}};
#ifdef DEMBRIDGE_HAVE_FEM
  if (mode == "fem")
  {
    const fem::Parameters p = fem::parse_parameters(prm);
    const fem::MeshEstimate e = fem::estimate_mesh(p);
    if (e.coarse_cells < 0) // a file that could not be counted: checked once it is read
      return nullptr;
    fem::check_mesh_fits(p, e, available);
    announce_mesh("FE mesh", e.cells, e.dofs, e.bytes);
    j["fe_cells"] = e.cells, j["fe_dofs"] = e.dofs, j["bytes"] = e.bytes;
    return j;
  }
#else
  if (mode == "fem")
    return nullptr;
#endif
  const dem::SizeEstimate estimate = dem::estimate_size(parse_dem_case(prm));
  j["particles"] = estimate.particles, j["bonds"] = estimate.bonds, j["bytes"] = estimate.bytes;
#ifdef DEMBRIDGE_HAVE_COUPLING
  if (mode == "coupled")
  {
    const coupling::ContinuumMeshSize fe =
        coupling::estimate_continuum_mesh(parse_coupled_case(prm));
    const double fe_bytes = fe.dofs * fem::bytes_per_dof(fem::ProblemKind::explicit_dynamics, 1);
    const double bytes = estimate.bytes + fe_bytes;
    if (fe_bytes >= estimate.bytes && available > 0 && bytes > available)
    {
      std::ostringstream text;
      text.precision(3);
      text << "Coupling/element size: the continuum mesh would have about " << fe.cells
           << " cells and " << fe.dofs << " DoFs, needing about " << human_bytes(fe_bytes)
           << " of memory (the particles " << human_bytes(estimate.bytes)
           << " more); this machine has " << human_bytes(available) << " available";
      throw dem::InputError(text.str());
    }
    dem::SizeEstimate both = estimate;
    both.bytes = bytes;
    dem::check_fits_in_memory(both, available);
    announce_mesh("coupled continuum", fe.cells, fe.dofs, fe_bytes);
    j["fe_cells"] = fe.cells, j["fe_dofs"] = fe.dofs, j["bytes"] = bytes;
    return j;
  }
#endif
  dem::check_fits_in_memory(estimate, available);
  return j;
}

double peak_memory_bytes()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024.0; // Linux: kilobytes
}
} // namespace dembridge::app
