#include "distributed/background_grid.h"
#include <algorithm>
#include <cmath>
#include <deal.II/grid/grid_generator.h>

namespace dembridge::distributed
{
std::array<unsigned, 3> BackgroundGrid::cells() const
{
  return {{coarse[0] << levels, coarse[1] << levels, coarse[2] << levels}};
}

std::size_t BackgroundGrid::n_cells() const
{
  const auto n = cells();
  return std::size_t(n[0]) * n[1] * n[2];
}

dem::Vec3 BackgroundGrid::upper() const
{
  const auto n = cells();
  return origin + cell_width * dem::Vec3(n[0], n[1], n[2]);
}

long BackgroundGrid::cell_of(const dem::Vec3& x) const
{
  const auto n = cells();
  long index = 0, stride = 1;
  for (int d = 0; d < 3; ++d)
  {
    const double t = std::floor((x[d] - origin[d]) / cell_width);
    if (!(t >= 0 && t < double(n[std::size_t(d)])))
      return -1;
    index += stride * long(t);
    stride *= long(n[std::size_t(d)]);
  }
  return index;
}

BackgroundGrid make_background_grid(const dem::Vec3& lower, const dem::Vec3& upper,
                                    double min_cell_width)
{
  if (!(min_cell_width > 0) || !((upper - lower).minCoeff() >= 0))
    throw std::logic_error("make_background_grid: an empty box or cell width");
  BackgroundGrid g;
  g.cell_width = min_cell_width;
  const dem::Vec3 extent = (upper - lower).cwiseMax(min_cell_width);
  // as many refinements as the shortest side holds: few trees (p4est keeps the coarse mesh on
  // every rank), cubic cells
  const double fewest = (extent / min_cell_width).minCoeff();
  g.levels = unsigned(std::clamp(std::floor(std::log2(fewest)), 0.0, 12.0));
  const double coarse_width = std::ldexp(min_cell_width, int(g.levels));
  for (int d = 0; d < 3; ++d)
    g.coarse[std::size_t(d)] = unsigned(std::max(1.0, std::ceil(extent[d] / coarse_width)));
  const dem::Vec3 centre = 0.5 * (lower + upper);
  for (int d = 0; d < 3; ++d)
    g.origin[d] = centre[d] - 0.5 * coarse_width * g.coarse[std::size_t(d)];
  return g;
}

BackgroundGrid background_grid_for(const dem::Model& model)
{
  const auto& p = model.particles;
  if (p.size() == 0)
    throw dem::InputError("Particles: a run on several MPI ranks needs particles");
  double longest = 0;
  for (std::size_t k = 0; k < model.bonds.size(); ++k)
  {
    const auto ia = std::size_t(model.bonds.a[k]), ib = std::size_t(model.bonds.b[k]);
    longest = std::max(longest, model.bonds.rest_length[k]);
    // a broken bond joins nothing (a resumed run's ends may lie far apart)
    if (model.bonds.state[k] != dem::BondState::broken)
      longest = std::max(longest, (p.position[ib] - p.position[ia]).norm());
  }
  const double largest_radius = *std::max_element(p.radius.begin(), p.radius.end());
  dem::Vec3 lo = p.position[0], hi = p.position[0];
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const dem::Vec3 r = dem::Vec3::Constant(p.radius[i]);
    lo = lo.cwiseMin(p.position[i] - r).cwiseMin(p.reference_position[i] - r);
    hi = hi.cwiseMax(p.position[i] + r).cwiseMax(p.reference_position[i] + r);
  }
  // at least the cut-off; and about 27 particles a cell in the specimen (a cell of deal.II's
  // mesh costs about a kilobyte, a particle's bonds half that: cells of one or two particles
  // would hold more memory than the particles)
  const double cut_off = longest > 0 ? 1.25 * longest : 2.5 * largest_radius;
  const double width = std::max(cut_off, std::cbrt(27 * (hi - lo).prod() / double(p.size())));
  const dem::Vec3 margin = dem::Vec3::Constant(width) + 0.05 * (hi - lo);
  return make_background_grid(lo - margin, hi + margin, width);
}

void create_background_mesh(dealii::parallel::distributed::Triangulation<3>& tria,
                            const BackgroundGrid& grid)
{
  const dem::Vec3 hi = grid.upper();
  dealii::GridGenerator::subdivided_hyper_rectangle(
      tria, {grid.coarse[0], grid.coarse[1], grid.coarse[2]},
      dealii::Point<3>(grid.origin[0], grid.origin[1], grid.origin[2]),
      dealii::Point<3>(hi[0], hi[1], hi[2]));
  tria.refine_global(grid.levels);
}
} // namespace dembridge::distributed
