// dembridge::fem — which rigid-body modes the supports of a static problem leave free.
//
// A rigid motion u(x) = t + w x (x - x0) is blocked by the Dirichlet DoFs when no (t, w) != 0
// vanishes on every one of them: with r_k(x, c) the c-component of mode k (three translations,
// three rotations about x0 scaled by the body size L), the modes left free span the null space of
// the 6 x 6 Gram matrix G = sum over fixed DoFs of r r^T. Checked before the solve, so that an
// unsupported body is named as such instead of CG failing to converge on a singular matrix.
#include "elastic_problem.h"

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <algorithm>
#include <map>

namespace dembridge::fem
{
using namespace dealii;

std::string ElasticProblem::free_rigid_body_modes() const
{
  // reference point and length: the centre and size of the body's bounding box
  Point<3> lo, hi;
  for (unsigned int d = 0; d < 3; ++d)
    lo[d] = std::numeric_limits<double>::max(), hi[d] = -std::numeric_limits<double>::max();
  for (const auto& cell : triangulation.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const auto v : cell->vertex_indices())
        for (unsigned int d = 0; d < 3; ++d)
        {
          lo[d] = std::min(lo[d], cell->vertex(v)[d]);
          hi[d] = std::max(hi[d], cell->vertex(v)[d]);
        }
  Point<3> centre;
  double size = 0;
  for (unsigned int d = 0; d < 3; ++d)
  {
    lo[d] = Utilities::MPI::min(lo[d], mpi_communicator);
    hi[d] = Utilities::MPI::max(hi[d], mpi_communicator);
    centre[d] = 0.5 * (lo[d] + hi[d]);
    size = std::max(size, hi[d] - lo[d]);
  }

  std::map<types::global_dof_index, Point<3>> support_points;
  DoFTools::map_dofs_to_support_points(mapping, dof_handler, support_points);
  std::vector<double> gram(36, 0.0);
  for (unsigned int c = 0; c < 3; ++c)
  {
    ComponentMask mask(3, false);
    mask.set(c, true);
    for (const auto dof : DoFTools::extract_dofs(dof_handler, mask))
    {
      // a Dirichlet line fixes the DoF outright (hanging-node lines have entries)
      const auto* entries = constraints.get_constraint_entries(dof);
      if (!constraints.is_constrained(dof) || (entries && !entries->empty()))
        continue;
      const auto found = support_points.find(dof);
      if (found == support_points.end())
        continue;
      const Tensor<1, 3> x = (found->second - centre) / size;
      double r[6] = {0, 0, 0, 0, 0, 0};
      r[c] = 1;
      for (unsigned int a = 0; a < 3; ++a) // (e_a x x)_c
        r[3 + a] = a == (c + 1) % 3 ? x[(c + 2) % 3] : a == (c + 2) % 3 ? -x[(c + 1) % 3] : 0.0;
      for (unsigned int i = 0; i < 6; ++i)
        for (unsigned int j = 0; j < 6; ++j)
          gram[6 * i + j] += r[i] * r[j];
    }
  }
  Utilities::MPI::sum(gram, mpi_communicator, gram);

  LAPACKFullMatrix<double> g(6, 6);
  for (unsigned int i = 0; i < 6; ++i)
    for (unsigned int j = 0; j < 6; ++j)
      g(i, j) = gram[6 * i + j];
  Vector<double> eigenvalues;
  FullMatrix<double> eigenvectors;
  const double largest = *std::max_element(gram.begin(), gram.end());
  g.compute_eigenvalues_symmetric(-1.0, 1e-10 * std::max(largest, 1.0), 0.0, eigenvalues,
                                  eigenvectors);
  static const char* names[6] = {"translation x",    "translation y",    "translation z",
                                 "rotation about x", "rotation about y", "rotation about z"};
  std::string free;
  for (unsigned int k = 0; k < eigenvalues.size(); ++k)
  {
    unsigned int dominant = 0;
    for (unsigned int i = 1; i < 6; ++i)
      if (std::abs(eigenvectors(i, k)) > std::abs(eigenvectors(dominant, k)))
        dominant = i;
    free += (free.empty() ? "" : ", ") + std::string(names[dominant]);
  }
  return free;
}
} // namespace dembridge::fem
