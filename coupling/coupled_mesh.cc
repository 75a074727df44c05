#include "coupling/coupled_mesh.h"
#include <algorithm>
#include <cmath>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <map>
#include <set>
#include <stdexcept>

namespace dembridge::coupling
{
using namespace dealii;

GridLines coupled_mesh_steps(const HandshakeGeometry& g, const GridLines& planes,
                             const Vec3& element_size, const double band_element_size,
                             const Vec3& far_element_size, const double growth)
{
  if (!(element_size.minCoeff() > 0) || !(band_element_size > 0))
    throw std::runtime_error("Coupling/element size: must be positive");
  const double tol = 1e-9 * (g.domain_hi - g.domain_lo).norm();
  // Per axis: break points (domain ends and band planes), then equal cells in each interval.
  GridLines steps;
  for (int d = 0; d < 3; ++d)
  {
    std::vector<double> points = {g.domain_lo[d], g.domain_hi[d]};
    points.insert(points.end(), planes[d].begin(), planes[d].end());
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end(),
                             [&](double a, double b) { return std::abs(a - b) < tol; }),
                 points.end());
    for (std::size_t k = 0; k + 1 < points.size(); ++k)
    {
      const double a = points[k], b = points[k + 1], mid = 0.5 * (a + b);
      // band intervals lie between the two planes of one coupled face
      bool band = false;
      for (std::size_t p = 0; p + 1 < planes[d].size(); p += 2)
        band = band || (mid > planes[d][p] && mid < planes[d][p + 1]);
      const double size = band ? band_element_size : element_size[d];
      auto touches = [&](double x)
      {
        return std::any_of(planes[d].begin(), planes[d].end(),
                           [&](double p) { return std::abs(p - x) < tol; });
      };
      const bool from_a = touches(a), from_b = touches(b);
      if (band || far_element_size[d] <= size || !(from_a || from_b))
      {
        const int n = std::max(1, int(std::lround((b - a) / size)));
        for (int i = 0; i < n; ++i)
          steps[d].push_back((b - a) / n);
        continue;
      }
      // graded: h, h g, h g^2, ... up to the far size from each end on a band plane, over the
      // interval (or its half when both ends touch), scaled to fill it exactly
      const double length = (from_a && from_b) ? 0.5 * (b - a) : b - a;
      std::vector<double> w;
      double sum = 0;
      for (double h = size; sum < length * (1 - 1e-12);
           h = std::min(h * growth, far_element_size[d]))
        w.push_back(h), sum += h;
      if (w.size() > 1 && sum - length > 0.5 * w.back()) // the last cell overshoots: drop it
        sum -= w.back(), w.pop_back();
      for (auto& x : w)
        x *= length / sum;
      std::vector<double> cells;
      if (from_a && from_b)
      {
        cells = w;
        cells.insert(cells.end(), w.rbegin(), w.rend());
      }
      else if (from_a)
        cells = w;
      else
        cells.assign(w.rbegin(), w.rend());
      steps[d].insert(steps[d].end(), cells.begin(), cells.end());
    }
  }
  return steps;
}

GridLines grid_lines(const Vec3& lo, const GridLines& steps)
{
  GridLines lines;
  for (int d = 0; d < 3; ++d)
  {
    lines[d] = {lo[d]};
    for (const double step : steps[d])
      lines[d].push_back(lines[d].back() + step);
  }
  return lines;
}

namespace
{
/// The box grid of the cell sizes @p steps with the particle-only cells cut out (file comment).
fem::BoundaryNames mesh_from_steps(const Handshake& h, const GridLines& steps,
                                   parallel::distributed::Triangulation<3>& tria,
                                   std::vector<RemovedShare>* removed)
{
  const auto& g = h.geometry();
  const double tol = 1e-9 * (g.domain_hi - g.domain_lo).norm();
  Triangulation<3> box;
  GridGenerator::subdivided_hyper_rectangle(
      box, std::vector<std::vector<double>>(steps.begin(), steps.end()),
      Point<3>(g.domain_lo[0], g.domain_lo[1], g.domain_lo[2]),
      Point<3>(g.domain_hi[0], g.domain_hi[1], g.domain_hi[2]));
  std::set<Triangulation<3>::active_cell_iterator> remove;
  // A cell goes when its centre and its eight Gauss points lie in the particle-only region, where
  // the continuum has neither stiffness (1 - alpha = 0) nor mass: a box's band planes are cell
  // faces, so there the centre decides alone; a volume's band cuts cells, and a cell it cuts keeps
  // mass at every node (Q1 shape values are positive at every Gauss point).
  for (const auto& cell : box.active_cell_iterators())
  {
    const Point<3> c = cell->center();
    const Tensor<1, 3> half = 0.5 * (cell->vertex(7) - cell->vertex(0)); // axis-aligned cells
    bool particle_only = h.in_particle_only(Vec3(c[0], c[1], c[2]));
    for (int q = 0; q < 8 && particle_only; ++q)
    {
      Vec3 x(c[0], c[1], c[2]);
      for (int d = 0; d < 3; ++d)
        x[d] += ((q >> d) & 1 ? 1 : -1) * half[d] / std::sqrt(3.0);
      particle_only = h.in_particle_only(x);
    }
    if (particle_only)
      remove.insert(cell);
  }
  if (removed)
  {
    std::map<unsigned int, double> share;
    for (const auto& cell : remove)
      for (const unsigned int v : cell->vertex_indices())
        share[cell->vertex_index(v)] += cell->measure() / 8;
    removed->clear();
    for (const auto& [v, volume] : share)
      removed->push_back({box.get_vertices()[v], volume});
  }
  Triangulation<3> cut;
  if (remove.empty())
    cut.copy_triangulation(box);
  else
    GridGenerator::create_triangulation_with_removed_cells(box, remove, cut);
  // Boundary ids by position: outer faces 0-5 (x-min, x-max, ...), the cut faces 6.
  for (const auto& cell : cut.active_cell_iterators())
    for (const auto& face : cell->face_iterators())
      if (face->at_boundary())
      {
        const Point<3> c = face->center();
        types::boundary_id id = 6;
        for (int d = 0; d < 3 && id == 6; ++d)
        {
          if (std::abs(c[d] - g.domain_lo[d]) < tol)
            id = 2 * d;
          else if (std::abs(c[d] - g.domain_hi[d]) < tol)
            id = 2 * d + 1;
        }
        face->set_boundary_id(id);
      }
  tria.copy_triangulation(cut);
  fem::BoundaryNames names = {{"x-min", {0, 2}}, {"x-max", {1, 2}}, {"y-min", {2, 2}},
                              {"y-max", {3, 2}}, {"z-min", {4, 2}}, {"z-max", {5, 2}}};
  if (!remove.empty())
    names["particle-region"] = {6, 2};
  return names;
}
} // namespace

fem::BoundaryNames
make_coupled_mesh(const Handshake& h, const Vec3& element_size, const double band_element_size,
                  parallel::distributed::Triangulation<3>& tria, std::vector<RemovedShare>* removed,
                  const Vec3& far_element_size, const double growth, const GridLines* fine_planes)
{
  return mesh_from_steps(
      h,
      coupled_mesh_steps(h.geometry(), fine_planes ? *fine_planes : h.band_planes(), element_size,
                         band_element_size, far_element_size, growth),
      tria, removed);
}

fem::BoundaryNames
make_coupled_mesh(const Handshake& h, const Vec3& element_size, const double band_element_size,
                  parallel::distributed::Triangulation<3>& tria, std::vector<RemovedShare>* removed,
                  const Vec3& far_element_size, const double growth, const GivenGridLines* grid)
{
  if (!grid)
    return make_coupled_mesh(h, element_size, band_element_size, tria, removed, far_element_size,
                             growth, static_cast<const GridLines*>(nullptr));
  GridLines steps;
  for (int d = 0; d < 3; ++d)
    for (std::size_t i = 0; i + 1 < grid->lines[d].size(); ++i)
      steps[d].push_back(grid->lines[d][i + 1] - grid->lines[d][i]);
  return mesh_from_steps(h, steps, tria, removed);
}
} // namespace dembridge::coupling
