// The columns' boundary area per volume by voro++, and the interface-compliance estimate
// (equations and sources in column_tessellation.h).
#include "app/studies/column_tessellation.h"
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>
#include <voro++/voro++.hh>

namespace dembridge::app
{
ColumnTessellation column_tessellation(const dem::ColumnarGrainsConfig& grains, const dem::Vec3& lo,
                                       const dem::Vec3& hi)
{
  if (!grains.enabled)
    throw dem::InputError("column tessellation: the case has no columnar grains");
  // (u, v): the plane across the columns, as column_seed has it (u along the axis after the
  // column axis, cyclically, v along the next)
  const int iu = (grains.axis + 1) % 3, iv = (grains.axis + 2) % 3;
  const double ulo = lo[iu], uhi = hi[iu], vlo = lo[iv], vhi = hi[iv];
  if (!(uhi > ulo && vhi > vlo))
    throw dem::InputError("column tessellation: the window is empty across the columns");
  const double a = dem::column_lattice_spacing(grains.diameter), h = a * std::sqrt(3.0) / 2;
  // A point's nearest seed lies within the hexagon's circumradius a / sqrt(3) of its node plus the
  // offset (at most jitter a); a seed reaches the window only if it lies within twice that of it.
  const double reach = 2 * (a / std::sqrt(3.0) + grains.jitter * a) + a;
  const double box_ulo = ulo - reach, box_uhi = uhi + reach;
  const double box_vlo = vlo - reach, box_vhi = vhi + reach;
  const long j0 = long(std::floor(box_vlo / h)) - 2, j1 = long(std::ceil(box_vhi / h)) + 2;

  std::vector<std::array<double, 2>> seeds;
  for (long j = j0; j <= j1; ++j)
  {
    const long i0 = long(std::floor(box_ulo / a - 0.5 * double(j))) - 2;
    const long i1 = long(std::ceil(box_uhi / a - 0.5 * double(j))) + 2;
    for (long i = i0; i <= i1; ++i)
    {
      const auto s = dem::column_seed(grains, i, j);
      if (s[0] > box_ulo && s[0] < box_uhi && s[1] > box_vlo && s[1] < box_vhi)
        seeds.push_back(s);
    }
  }
  // a slab of unit thickness along the axis: about 5 seeds per block of voro++'s grid
  const int nu = std::max(1, int((box_uhi - box_ulo) / a / 2)),
            nv = std::max(1, int((box_vhi - box_vlo) / a / 2));
  voro::container con(box_ulo, box_uhi, box_vlo, box_vhi, 0.0, 1.0, nu, nv, 1, false, false, false,
                      8);
  for (std::size_t k = 0; k < seeds.size(); ++k)
    con.put(int(k), seeds[k][0], seeds[k][1], 0.5);

  ColumnTessellation out;
  out.window_area = (uhi - ulo) * (vhi - vlo);
  double shared_area = 0;
  voro::c_loop_all loop(con);
  voro::voronoicell_neighbor cell;
  std::vector<int> neighbours;
  std::vector<double> areas;
  // window sides: keep r . n <= d (r from the seed; voro++ keeps r . v <= rsq / 2), ids below
  // voro++'s own walls (-1 to -6)
  if (loop.start())
    do
      if (con.compute_cell(cell, loop))
      {
        double x, y, z;
        loop.pos(x, y, z);
        if (!cell.nplane(1, 0, 0, 2 * (uhi - x), -7) || !cell.nplane(-1, 0, 0, 2 * (x - ulo), -8) ||
            !cell.nplane(0, 1, 0, 2 * (vhi - y), -9) || !cell.nplane(0, -1, 0, 2 * (y - vlo), -10))
          continue; // the cell lies outside the window
        const double volume = cell.volume();
        if (!(volume > 0))
          continue;
        out.cell_area_sum += volume; // unit thickness
        ++out.cells;
        cell.neighbors(neighbours);
        cell.face_areas(areas);
        for (std::size_t f = 0; f < areas.size(); ++f)
          if (neighbours[f] >= 0)
            shared_area += areas[f];
      }
    while (loop.inc());
  if (!(std::abs(out.cell_area_sum - out.window_area) <= 1e-9 * out.window_area))
  {
    std::ostringstream msg;
    msg << "column tessellation: the cut cells cover " << out.cell_area_sum
        << " m^2 of the window's " << out.window_area << " m^2";
    throw std::runtime_error(msg.str());
  }
  out.boundary_area_per_volume = 0.5 * shared_area / out.window_area;
  return out;
}

double interface_compliance_youngs_modulus(double E, double S_v, double B_N, double B_T)
{
  return 1.0 / (1.0 / E + S_v * (3 * B_N + B_T) / 8);
}
} // namespace dembridge::app
