// read_region_volume (region_volume.h): deal.II reads the gmsh file, after the checks FE meshes
// get (fem/mesh.h), so that a malformed file is refused with its line instead of hanging the
// reader.
#include "coupling/region_volume.h"
#include "fem/mesh.h"

#include <deal.II/grid/tria.h>

#include <fstream>
#include <stdexcept>

namespace dembridge::coupling
{
namespace
{
/// fem's messages name FEM/Mesh/file; this file is read for another key.
std::runtime_error rekeyed(const std::exception& e, const std::string& key)
{
  std::string what = e.what();
  const std::string fe_key = "FEM/Mesh/file";
  if (what.rfind(fe_key, 0) == 0)
    what = key + what.substr(fe_key.size());
  return std::runtime_error(what);
}

Vec3 to_vec(const dealii::Point<3>& x)
{
  return {x[0], x[1], x[2]};
}
} // namespace

RegionVolume read_region_volume(const std::string& name, const std::string& key)
{
  dealii::Triangulation<3> tria;
  std::string file;
  try
  {
    file = fem::resolve_mesh_file(name);
    std::ifstream sections(file);
    fem::check_msh_sections(sections, file);
    fem::read_msh_file(file, tria, "gmsh volume mesh");
  }
  catch (const std::exception& e)
  {
    throw rekeyed(e, key);
  }
  std::vector<Tetrahedron> tets;
  std::vector<Triangle> boundary;
  for (const auto& cell : tria.active_cell_iterators())
  {
    if (cell->reference_cell() == dealii::ReferenceCells::Tetrahedron)
      tets.push_back({{to_vec(cell->vertex(0)), to_vec(cell->vertex(1)), to_vec(cell->vertex(2)),
                       to_vec(cell->vertex(3))}});
    else if (cell->reference_cell() == dealii::ReferenceCells::Hexahedron)
    {
      // Kuhn's split around the diagonal v0-v7 (deal.II numbers a hexahedron's vertices
      // lexicographically: v = i + 2 j + 4 k)
      static constexpr int split[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                          {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
      for (const auto& s : split)
        tets.push_back({{to_vec(cell->vertex(s[0])), to_vec(cell->vertex(s[1])),
                         to_vec(cell->vertex(s[2])), to_vec(cell->vertex(s[3]))}});
    }
    else
      throw std::runtime_error(key + ": '" + file +
                               "' holds cells other than tetrahedra and "
                               "hexahedra (mesh the region with one of them)");
    for (const auto& face : cell->face_iterators())
      if (face->at_boundary())
      {
        if (face->n_vertices() == 3)
          boundary.push_back(
              {{to_vec(face->vertex(0)), to_vec(face->vertex(1)), to_vec(face->vertex(2))}});
        else // a quadrilateral (lexicographic vertices): two triangles
        {
          boundary.push_back(
              {{to_vec(face->vertex(0)), to_vec(face->vertex(1)), to_vec(face->vertex(3))}});
          boundary.push_back(
              {{to_vec(face->vertex(0)), to_vec(face->vertex(3)), to_vec(face->vertex(2))}});
        }
      }
  }
  try
  {
    return RegionVolume(std::move(tets), std::move(boundary), key);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(std::string(e.what()) + " ('" + file + "')");
  }
}
} // namespace dembridge::coupling
