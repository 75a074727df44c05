// dembridge::fem — coarse meshes: generated boxes and gmsh files, with named boundaries.
#pragma once

#include "parameters.h"

#include <deal.II/distributed/tria.h>

#include <istream>
#include <map>
#include <string>

namespace dembridge::fem
{
/// Boundary name -> boundary id. Box faces are x-min=0, x-max=1, y-min=2, y-max=3, z-min=4,
/// z-max=5 (GridGenerator colorize). gmsh physical groups keep their physical tag as id; groups
/// of dimension 1 (lines) are listed with dimension 1 so that a load on them can be refused.
struct BoundaryName
{
  dealii::types::boundary_id id;
  int dimension;
};
using BoundaryNames = std::map<std::string, BoundaryName>;

/// Build the coarse mesh described by @p p into @p tria and refine it p.refinements times.
/// Throws std::runtime_error naming FEM/Mesh/file for a missing or unreadable mesh.
BoundaryNames make_mesh(const Parameters& p, dealii::parallel::distributed::Triangulation<3>& tria);

/// Look a boundary name up; throws std::runtime_error naming @p where and the known names.
dealii::types::boundary_id find_boundary(const BoundaryNames& names, const std::string& name,
                                         const std::string& where);

/// The mesh file to open: @p file if it exists, else (relative paths) the file of that name in
/// the build's meshes folder, where meshes/*.geo are meshed. Throws naming FEM/Mesh/file.
std::string resolve_mesh_file(const std::string& file);

/// Read the $PhysicalNames section of a .msh file (versions 2.2 and 4.1); throws
/// std::runtime_error naming FEM/Mesh/file for a malformed section.
BoundaryNames read_physical_names(const std::string& file);
/// The same from a stream; @p file names it in messages.
BoundaryNames read_physical_names(std::istream& in, const std::string& file);

/// Checks a .msh text before deal.II reads it (msh_check.cc): every $Section closed by its
/// $EndSection before the next one opens (deal.II's reader loops forever on some files that
/// break this: fuzz/findings/), the format version 2.2 or 4.1 (ASCII), and the node and element
/// sections (and 4.1's $Entities) consistent with their counts, every element node defined;
/// throws std::runtime_error naming FEM/Mesh/file, @p file and the line otherwise.
void check_msh_sections(std::istream& in, const std::string& file);

/// deal.II's read_msh of @p file (checked first with check_msh_sections) into @p tria; throws
/// std::runtime_error "FEM/Mesh/file: cannot read 'FILE' as a DESCRIPTION: <deal.II's reason>".
void read_msh_file(const std::string& file, dealii::Triangulation<3>& tria,
                   const std::string& description);

} // namespace dembridge::fem
