// The fixed-region counterpart of an adaptive case: the final region's cells (fixed_region.h).
#include "coupling/fixed_region.h"

#include <fstream>
#include <iomanip>
#include <map>
#include <stdexcept>

namespace dembridge::coupling
{
std::size_t RegionCells::n_cells() const
{
  std::size_t n = 0;
  for (const auto& r : runs)
    n += std::size_t(r[1] - r[0]);
  return n;
}

nlohmann::json RegionCells::to_json() const
{
  return {{"lines", {lines[0], lines[1], lines[2]}}, {"runs", runs}};
}

RegionCells RegionCells::from_json(const nlohmann::json& j, const std::string& where)
{
  RegionCells c;
  try
  {
    for (int d = 0; d < 3; ++d)
      c.lines[d] = j.at("lines").at(d).get<std::vector<double>>();
    c.runs = j.at("runs").get<std::vector<std::array<int, 4>>>();
  }
  catch (const nlohmann::json::exception& e)
  {
    throw std::runtime_error(where + ": not a region's cells (" + e.what() + ")");
  }
  for (int d = 0; d < 3; ++d)
    for (std::size_t k = 1; k < c.lines[d].size(); ++k)
      if (!(c.lines[d][k] > c.lines[d][k - 1]))
        throw std::runtime_error(where + ": the cell faces along " + std::string(1, "xyz"[d]) +
                                 " are not ascending");
  const int n[3] = {int(c.lines[0].size()) - 1, int(c.lines[1].size()) - 1,
                    int(c.lines[2].size()) - 1};
  for (const auto& r : c.runs)
    if (r[0] < 0 || r[1] <= r[0] || r[1] > n[0] || r[2] < 0 || r[2] >= n[1] || r[3] < 0 ||
        r[3] >= n[2])
      throw std::runtime_error(where + ": a run of cells lies outside its cell faces");
  if (c.runs.empty())
    throw std::runtime_error(where + ": the region has no cells");
  return c;
}

RegionCells region_cells(const AdaptiveRegion& region)
{
  const GridLines& lines = region.lines();
  const auto& cells = region.cells();
  const int n[3] = {int(lines[0].size()) - 1, int(lines[1].size()) - 1, int(lines[2].size()) - 1};
  auto at = [&](int i, int j, int k)
  { return cells[(std::size_t(k) * n[1] + std::size_t(j)) * n[0] + std::size_t(i)] != 0; };
  // the bounding box in cell indices, then the runs relative to it
  int lo[3] = {n[0], n[1], n[2]}, hi[3] = {-1, -1, -1};
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        if (at(i, j, k))
        {
          const int idx[3] = {i, j, k};
          for (int d = 0; d < 3; ++d)
            lo[d] = std::min(lo[d], idx[d]), hi[d] = std::max(hi[d], idx[d]);
        }
  RegionCells c;
  if (hi[0] < 0)
    return c;
  for (int d = 0; d < 3; ++d)
    c.lines[d].assign(lines[d].begin() + lo[d], lines[d].begin() + hi[d] + 2);
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
        if (at(i, j, k))
        {
          int end = i;
          while (end <= hi[0] && at(end, j, k))
            ++end;
          c.runs.push_back({{i - lo[0], end - lo[0], j - lo[1], k - lo[2]}});
          i = end;
        }
  return c;
}

void write_region_mesh(const RegionCells& cells, const std::filesystem::path& file)
{
  // gmsh's ASCII format 2.2, the one gmsh writes with -format msh22 (deal.II's GridOut writes
  // the older $NOD format); one node per grid point used, numbered from 1 as met
  std::map<std::array<int, 3>, std::size_t> node_of;
  std::vector<std::array<int, 3>> nodes;
  std::vector<std::array<std::size_t, 8>> hexes;
  // a gmsh hexahedron: the lower face counter-clockwise seen from above, then the upper one
  static constexpr int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                       {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& r : cells.runs)
    for (int i = r[0]; i < r[1]; ++i)
    {
      std::array<std::size_t, 8> hex{};
      for (int v = 0; v < 8; ++v)
      {
        const std::array<int, 3> at{{i + corner[v][0], r[2] + corner[v][1], r[3] + corner[v][2]}};
        const auto [it, added] = node_of.emplace(at, nodes.size() + 1);
        if (added)
          nodes.push_back(at);
        hex[v] = it->second;
      }
      hexes.push_back(hex);
    }
  std::ofstream out(file);
  out << std::setprecision(17) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n"
      << nodes.size() << '\n';
  for (std::size_t n = 0; n < nodes.size(); ++n)
    out << n + 1 << ' ' << cells.lines[0][nodes[n][0]] << ' ' << cells.lines[1][nodes[n][1]] << ' '
        << cells.lines[2][nodes[n][2]] << '\n';
  out << "$EndNodes\n$Elements\n" << hexes.size() << '\n';
  for (std::size_t e = 0; e < hexes.size(); ++e)
  {
    out << e + 1 << " 5 2 1 1"; // a hexahedron, physical and elementary tag 1
    for (const auto n : hexes[e])
      out << ' ' << n;
    out << '\n';
  }
  out << "$EndElements\n";
  out.close();
  if (!out)
    throw std::runtime_error(file.string() + ": cannot write the region's cells");
}
} // namespace dembridge::coupling
