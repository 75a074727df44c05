// dembridge::fem — coarse meshes: generated boxes and gmsh files, with named boundaries.
#include "mesh.h"

#include "dem/core/available_memory.h"
#include "mesh_estimate.h"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace dembridge::fem
{
BoundaryNames read_physical_names(std::istream& in, const std::string& file)
{
  BoundaryNames names;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("$PhysicalNames", 0) == 0)
    {
      long n = 0;
      if (!(in >> n) || n < 0)
        throw std::runtime_error("FEM/Mesh/file: bad $PhysicalNames count in " + file);
      for (long i = 0; i < n; ++i)
      {
        int dimension = 0;
        long tag = 0;
        std::string name;
        // a short or malformed section ends the loop here instead of running n times
        if (!(in >> dimension >> tag) || tag < 0 ||
            tag >= long(dealii::numbers::internal_face_boundary_id))
          throw std::runtime_error("FEM/Mesh/file: bad $PhysicalNames entry in " + file);
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

BoundaryNames read_physical_names(const std::string& file)
{
  std::ifstream in(file);
  return read_physical_names(in, file);
}

std::string resolve_mesh_file(const std::string& file)
{
  namespace fs = std::filesystem;
  if (fs::is_regular_file(file))
    return file;
  std::error_code ec;
  if (fs::is_directory(file, ec))
    throw std::runtime_error("FEM/Mesh/file: '" + file +
                             "' is a directory, not a mesh file (give the .msh file)");
  // the paths tried, absolute: a relative path is resolved against the working directory,
  // which `dembridge run` sets to the case file's folder
  std::string tried = fs::absolute(file).lexically_normal().string();
#ifdef DEMBRIDGE_MESH_DIR
  const fs::path generated = fs::path(DEMBRIDGE_MESH_DIR) / fs::path(file).filename();
  if (fs::path(file).is_relative() && fs::is_regular_file(generated))
    return generated.string();
  if (fs::path(file).is_relative())
    tried += " and " + generated.lexically_normal().string();
#endif
  throw std::runtime_error("FEM/Mesh/file: mesh file '" + file + "' does not exist (looked for " +
                           tried + ")");
}

namespace
{
/// Refuses refinements whose mesh the machine cannot hold, before refining (mesh_estimate.h;
/// the memory guard checks the estimate before the coarse mesh is read, this the mesh read).
void check_refined_mesh_fits(const Parameters& p, double coarse_cells)
{
  check_mesh_fits(p, estimate_refined_mesh(p, coarse_cells), available_memory_bytes());
}

constexpr dealii::types::boundary_id removed_boundary_id = 6;

bool has_remove_box(const Parameters& p)
{
  for (unsigned int d = 0; d < 3; ++d)
    if (!(p.remove_upper[d] > p.remove_lower[d]))
      return false;
  return true;
}

/// Step sizes along axis d: cell faces on the box ends and on every plane of the remove box and
/// the patches inside it; each interval divided evenly into cells of about the subdivisions'
/// size (at least one).
std::vector<double> fitted_steps(const Parameters& p, unsigned int d)
{
  const double lo = p.box_lower[d], hi = p.box_upper[d];
  const double h = (hi - lo) / std::max(1u, p.subdivisions[d]);
  const double tolerance = 1e-9 * (hi - lo);
  std::vector<double> planes{lo, hi};
  auto add = [&](double x)
  {
    if (x > lo + tolerance && x < hi - tolerance)
      planes.push_back(x);
  };
  if (has_remove_box(p))
    add(p.remove_lower[d]), add(p.remove_upper[d]);
  if (p.fit_planes)
    for (const auto& patch : p.patches)
      add(patch.lower[d]), add(patch.upper[d]);
  std::sort(planes.begin(), planes.end());
  std::vector<double> steps;
  for (std::size_t k = 0; k + 1 < planes.size(); ++k)
  {
    const double length = planes[k + 1] - planes[k];
    if (length <= tolerance)
      continue;
    const long n = std::max(1L, std::lround(length / h));
    steps.insert(steps.end(), std::size_t(n), length / double(n));
  }
  return steps;
}

/// The box mesh on fitted planes (fitted_steps), without the cells of the remove box; every
/// boundary face is named by where it lies: on a box face (x-min = 0 ... z-max = 5, as
/// GridGenerator's colorize numbers them) or, inside the box, on the removed cells' surface.
void make_fitted_box(const Parameters& p, dealii::parallel::distributed::Triangulation<3>& tria)
{
  std::vector<std::vector<double>> steps(3);
  for (unsigned int d = 0; d < 3; ++d)
    steps[d] = fitted_steps(p, d);
  dealii::Triangulation<3> full;
  dealii::GridGenerator::subdivided_hyper_rectangle(full, steps, p.box_lower, p.box_upper);
  if (has_remove_box(p))
  {
    std::set<dealii::Triangulation<3>::active_cell_iterator> removed;
    for (const auto& cell : full.active_cell_iterators())
    {
      const auto c = cell->center();
      bool inside = true;
      for (unsigned int d = 0; d < 3; ++d)
        inside = inside && c[d] > p.remove_lower[d] && c[d] < p.remove_upper[d];
      if (inside)
        removed.insert(cell);
    }
    if (removed.empty())
      throw std::runtime_error("FEM/Mesh/remove box: no cell centre lies inside it");
    if (removed.size() == full.n_active_cells())
      throw std::runtime_error("FEM/Mesh/remove box: it removes every cell");
    dealii::GridGenerator::create_triangulation_with_removed_cells(full, removed, tria);
  }
  else
    tria.copy_triangulation(full);
  const double tolerance = 1e-9 * (p.box_upper - p.box_lower).norm();
  for (const auto& cell : tria.cell_iterators())
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary())
      {
        const auto c = cell->face(f)->center();
        dealii::types::boundary_id id = removed_boundary_id;
        for (unsigned int d = 0; d < 3; ++d)
          if (std::abs(c[d] - p.box_lower[d]) < tolerance)
            id = 2 * d;
          else if (std::abs(c[d] - p.box_upper[d]) < tolerance)
            id = 2 * d + 1;
        cell->face(f)->set_boundary_id(id);
      }
}

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
    const char* faces[6] = {"x-min", "x-max", "y-min", "y-max", "z-min", "z-max"};
    for (unsigned int f = 0; f < 6; ++f)
      names[faces[f]] = {static_cast<dealii::types::boundary_id>(f), 2};
    if (has_remove_box(p) || p.fit_planes)
    {
      make_fitted_box(p, tria);
      if (has_remove_box(p))
        names["removed"] = {removed_boundary_id, 2};
    }
    else
    {
      const std::vector<unsigned int> repetitions(p.subdivisions.begin(), p.subdivisions.end());
      dealii::GridGenerator::subdivided_hyper_rectangle(tria, repetitions, p.box_lower, p.box_upper,
                                                        /*colorize=*/true);
    }
  }
  else
  {
    const std::string file = resolve_mesh_file(p.mesh_file);
    {
      std::ifstream sections(file);
      check_msh_sections(sections, file);
    }
    names = read_physical_names(file);
    read_msh_file(file, tria, "hexahedral gmsh mesh");
  }
  check_refined_mesh_fits(p, double(tria.n_global_active_cells()));
  tria.refine_global(p.refinements);
  apply_patches(p.patches, tria, names);
  return names;
}

void read_msh_file(const std::string& file, dealii::Triangulation<3>& tria,
                   const std::string& description)
{
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
    throw std::runtime_error("FEM/Mesh/file: cannot read '" + file + "' as a " + description +
                             (reason.empty() ? "" : ": " + reason));
  }
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
