// dembridge::fem — how big an FE mesh will be before it is built, for the memory guard: a mesh
// the machine cannot hold is refused at once with the figures, instead of minutes inside
// deal.II's triangulation and a kill by the kernel.
//   coarse cells   box: the product of the box subdivisions; gmsh: the volume elements the
//                  file's $Elements section lists (2.2 and 4.1, counted without reading nodes)
//   cells          coarse cells x 8^refinements
//   DoFs           3 per node: box 3 prod_d (p n_d 2^R + 1), any other mesh about
//                  3 (p C^(1/3) + 1)^3 for C cells of degree p
//   memory         DoFs x bytes per DoF (bytes_per_dof)
#pragma once

#include "parameters.h"

#include <string>

namespace dembridge::fem
{
struct MeshEstimate
{
  double coarse_cells = 0; ///< before refinement (< 0: unknown, the file could not be counted)
  double cells = 0;        ///< after refinement
  double dofs = 0;
  double bytes = 0; ///< peak memory of building and solving it (B)
};

/// Peak bytes per DoF of a run on the mesh: static solves about 6 kB (Q1) and 11 kB (Q2) (the
/// cautious end of bench/RESULTS_FEM.md: matrix, AMG hierarchy, vectors); explicit dynamics and
/// coupled runs (Q1) 3 kB (measured 2.0 kB per DoF over the process's start: an FE bar of
/// 140 k DoFs, coupled_compression.prm with 454 k FE DoFs 2.1 kB), Q2 as static.
double bytes_per_dof(ProblemKind problem, unsigned int degree);

/// Volume elements (3-D element types) in the $Elements section of the gmsh file @p file;
/// -1 when the file cannot be read or counted (the mesh reader then reports why).
double count_msh_volume_elements(const std::string& file);

/// The mesh FEM/Mesh describes (the box, or the file resolve_mesh_file finds), before building it.
MeshEstimate estimate_mesh(const Parameters& p);

/// The same from a known number of coarse cells (after reading the coarse mesh).
MeshEstimate estimate_refined_mesh(const Parameters& p, double coarse_cells);

/// Throws std::runtime_error naming the key that sets the size (FEM/Mesh/refinements when there
/// are refinements, else FEM/Mesh/box subdivisions or FEM/Mesh/file), the cells, DoFs and memory
/// of @p e and @p available, when e.bytes exceeds @p available (> 0).
void check_mesh_fits(const Parameters& p, const MeshEstimate& e, double available);
} // namespace dembridge::fem
