// dembridge::fem — how big an FE mesh will be before it is built (mesh_estimate.h).
#include "mesh_estimate.h"

#include "dem/core/available_memory.h"
#include "mesh.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dembridge::fem
{
double bytes_per_dof(const ProblemKind problem, const unsigned int degree)
{
  if (degree == 1)
    return problem == ProblemKind::static_elasticity ? 6e3 : 3e3;
  return 11e3;
}

namespace
{
/// gmsh element types of dimension 3 (gmsh manual, MSH file format: 4 tetrahedron, 5
/// hexahedron, 6 prism, 7 pyramid, 11-14 and 17-19 their second-order forms).
bool is_volume_type(const long type)
{
  return (type >= 4 && type <= 7) || (type >= 11 && type <= 14) || (type >= 17 && type <= 19);
}
} // namespace

double count_msh_volume_elements(const std::string& file)
{
  std::ifstream in(file);
  std::string line, version;
  while (std::getline(in, line) && line.rfind("$MeshFormat", 0) != 0)
  {
  }
  if (!std::getline(in, line))
    return -1;
  version = line.substr(0, line.find(' '));
  while (std::getline(in, line) && line.rfind("$Elements", 0) != 0)
  {
  }
  if (!in)
    return -1;
  double volume = 0;
  if (version == "2.2")
  {
    long n = 0;
    if (!(in >> n) || n < 0)
      return -1;
    std::getline(in, line);
    for (long k = 0; k < n && std::getline(in, line); ++k)
    {
      std::istringstream fields(line);
      long number = 0, type = 0;
      if (!(fields >> number >> type))
        return -1;
      volume += is_volume_type(type);
    }
    return volume;
  }
  if (version != "4.1")
    return -1;
  // blocks "dimension tag type count", each followed by its count element lines
  long blocks = 0, total = 0, min_tag = 0, max_tag = 0;
  if (!(in >> blocks >> total >> min_tag >> max_tag) || blocks < 0)
    return -1;
  for (long b = 0; b < blocks; ++b)
  {
    long dimension = 0, tag = 0, type = 0, count = 0;
    if (!(in >> dimension >> tag >> type >> count) || count < 0)
      return -1;
    std::getline(in, line);
    if (dimension == 3)
      volume += double(count);
    for (long k = 0; k < count && std::getline(in, line); ++k)
    {
    }
  }
  return volume;
}

MeshEstimate estimate_refined_mesh(const Parameters& p, const double coarse_cells)
{
  MeshEstimate e;
  e.coarse_cells = coarse_cells;
  const double split = std::pow(2.0, p.refinements); // cells per coarse cell along an axis
  e.cells = coarse_cells * split * split * split;
  e.dofs = 3 * std::pow(p.degree * std::cbrt(e.cells) + 1, 3);
  e.bytes = e.dofs * bytes_per_dof(p.problem, p.degree);
  return e;
}

MeshEstimate estimate_mesh(const Parameters& p)
{
  if (p.mesh_source == MeshSource::box)
  {
    MeshEstimate e = estimate_refined_mesh(
        p, double(p.subdivisions[0]) * double(p.subdivisions[1]) * double(p.subdivisions[2]));
    const double split = std::pow(2.0, p.refinements);
    e.dofs = 3;
    for (int d = 0; d < 3; ++d)
      e.dofs *= p.degree * double(p.subdivisions[d]) * split + 1;
    e.bytes = e.dofs * bytes_per_dof(p.problem, p.degree);
    return e;
  }
  double coarse = -1;
  try
  {
    coarse = count_msh_volume_elements(resolve_mesh_file(p.mesh_file));
  }
  catch (const std::exception&) // a missing file: the mesh reader says so
  {
  }
  if (coarse < 0)
    return MeshEstimate{-1, 0, 0, 0};
  return estimate_refined_mesh(p, coarse);
}

void check_mesh_fits(const Parameters& p, const MeshEstimate& e, const double available)
{
  if (!(available > 0) || !(e.bytes > available))
    return;
  std::ostringstream text;
  text.precision(3);
  if (p.refinements > 0)
    text << "FEM/Mesh/refinements: " << p.refinements << " refinements of the " << e.coarse_cells
         << " coarse cells make " << e.cells << " cells";
  else if (p.mesh_source == MeshSource::box)
    text << "FEM/Mesh/box subdivisions: the box mesh has " << e.cells << " cells";
  else
    text << "FEM/Mesh/file: the mesh has " << e.cells << " cells";
  text << " and about " << e.dofs << " DoFs (Q" << p.degree << "), needing about "
       << human_bytes(e.bytes) << " of memory; this machine has " << human_bytes(available)
       << " available";
  throw std::runtime_error(text.str());
}
} // namespace dembridge::fem
