// dembridge::fem — coarse meshes: generated boxes and gmsh files, with named boundaries.
#include "mesh.h"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dembridge::fem
{
BoundaryNames read_physical_names(const std::string& file)
{
  std::ifstream in(file);
  BoundaryNames names;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("$PhysicalNames", 0) == 0)
    {
      unsigned int n = 0;
      in >> n;
      for (unsigned int i = 0; i < n; ++i)
      {
        int dimension = 0;
        unsigned int tag = 0;
        std::string name;
        in >> dimension >> tag;
        std::getline(in, name);
        const auto q0 = name.find('"');
        const auto q1 = name.rfind('"');
        if (q0 == std::string::npos || q1 <= q0)
          throw std::runtime_error("FEM/Mesh/file: bad $PhysicalNames entry in " + file);
        if (dimension < 3)
          names[name.substr(q0 + 1, q1 - q0 - 1)] = {static_cast<dealii::types::boundary_id>(tag),
                                                     dimension};
      }
      break;
    }
  return names;
}

std::string resolve_mesh_file(const std::string& file)
{
  namespace fs = std::filesystem;
  if (fs::is_regular_file(file))
    return file;
#ifdef DEMBRIDGE_MESH_DIR
  const fs::path generated = fs::path(DEMBRIDGE_MESH_DIR) / fs::path(file).filename();
  if (fs::path(file).is_relative() && fs::is_regular_file(generated))
    return generated.string();
#endif
  throw std::runtime_error("FEM/Mesh/file: mesh file '" + file + "' does not exist");
}

namespace
{
/// Boundary faces whose centres lie in a patch box get the patch's new boundary id. Done after
/// the global refinement (the mesh is not refined again), on every cell a rank sees, so that
/// ghost faces carry the same ids as their owners'.
void apply_patches(const std::vector<BoundaryPatch>& patches,
                   dealii::parallel::distributed::Triangulation<3>& tria, BoundaryNames& names)
{
  if (patches.empty())
    return;
  const std::string where = "FEM/Mesh/patches";
  unsigned int next = 0;
  for (const auto& [name, b] : names)
    next = std::max<unsigned int>(next, b.id + 1u);
  for (const auto id : tria.get_boundary_ids())
    next = std::max<unsigned int>(next, id + 1u);
  next = dealii::Utilities::MPI::max(next, tria.get_communicator());
  double min_diameter = std::numeric_limits<double>::max();
  for (const auto& cell : tria.active_cell_iterators())
    if (cell->is_locally_owned())
      min_diameter = std::min(min_diameter, cell->diameter());
  const double tolerance =
      1e-6 * dealii::Utilities::MPI::min(min_diameter, tria.get_communicator());
  for (const auto& patch : patches)
  {
    if (names.count(patch.name))
      throw std::runtime_error(where + ": '" + patch.name + "' already names a boundary");
    const auto id = static_cast<dealii::types::boundary_id>(next++);
    unsigned int n_faces = 0;
    for (const auto& cell : tria.active_cell_iterators())
      if (!cell->is_artificial())
        for (const auto& face : cell->face_iterators())
        {
          if (!face->at_boundary())
            continue;
          const dealii::Point<3> c = face->center();
          bool inside = true;
          for (unsigned int d = 0; d < 3; ++d)
            inside =
                inside && c[d] >= patch.lower[d] - tolerance && c[d] <= patch.upper[d] + tolerance;
          if (!inside)
            continue;
          face->set_boundary_id(id);
          n_faces += cell->is_locally_owned();
        }
    if (dealii::Utilities::MPI::sum(n_faces, tria.get_communicator()) == 0)
      throw std::runtime_error(where + ": patch '" + patch.name +
                               "' contains no boundary face centre");
    names[patch.name] = {id, 2};
  }
}
} // namespace

BoundaryNames make_mesh(const Parameters& p, dealii::parallel::distributed::Triangulation<3>& tria)
{
  BoundaryNames names;
  if (p.mesh_source == MeshSource::box)
  {
    const std::vector<unsigned int> repetitions(p.subdivisions.begin(), p.subdivisions.end());
    dealii::GridGenerator::subdivided_hyper_rectangle(tria, repetitions, p.box_lower, p.box_upper,
                                                      /*colorize=*/true);
    const char* faces[6] = {"x-min", "x-max", "y-min", "y-max", "z-min", "z-max"};
    for (unsigned int f = 0; f < 6; ++f)
      names[faces[f]] = {static_cast<dealii::types::boundary_id>(f), 2};
  }
  else
  {
    const std::string file = resolve_mesh_file(p.mesh_file);
    names = read_physical_names(file);
    std::ifstream in(file);
    dealii::GridIn<3> grid_in;
    grid_in.attach_triangulation(tria);
    try
    {
      grid_in.read_msh(in);
    }
    catch (const std::exception& e)
    {
      std::string what = e.what();
      // deal.II messages span lines; keep the line that says what went wrong.
      std::istringstream lines(what);
      std::string line, reason;
      while (std::getline(lines, line))
        if (line.find("Additional information") != std::string::npos)
          std::getline(lines, reason);
      throw std::runtime_error("FEM/Mesh/file: cannot read '" + file +
                               "' as a hexahedral gmsh mesh" +
                               (reason.empty() ? "" : ": " + reason));
    }
  }
  tria.refine_global(p.refinements);
  apply_patches(p.patches, tria, names);
  return names;
}

dealii::types::boundary_id find_boundary(const BoundaryNames& names, const std::string& name,
                                         const std::string& where)
{
  const auto it = names.find(name);
  if (it == names.end())
  {
    std::string known;
    for (const auto& [n, b] : names)
      known += (known.empty() ? "" : ", ") + n;
    throw std::runtime_error(where + ": boundary '" + name +
                             "' is not a face or physical group of the mesh (known: " +
                             (known.empty() ? "none" : known) + ")");
  }
  return it->second.id;
}

} // namespace dembridge::fem
