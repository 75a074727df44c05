#pragma once
// A particle region of any shape: the volume of a gmsh mesh ("the particle region as a
// box or any gmsh volume inside the FE domain").
//
// The volume is kept as tetrahedra (a hexahedron is split into six around its diagonal v0-v7,
// Kuhn's split) and its boundary as triangles (a quadrilateral face into two). Two queries:
//   contains(x)  x lies in a tetrahedron, by barycentric coordinates with a tolerance of 1e-9 of
//                the tetrahedron's size: points on the surface count as inside;
//   SurfaceDistance::distance(x)
//                the Euclidean distance from x to the nearest triangle of a surface (the part of
//                the region's boundary inside the FE domain: the coupled surface), the closest
//                point on a triangle after Ericson, Real-Time Collision Detection (2005), 5.1.5.
//                Only distances up to a reach are needed (the band width: the weights are
//                constant beyond it), so each triangle is listed in the cells of a uniform grid
//                that its box, grown by the reach, overlaps; a point farther than the reach from
//                every triangle gets +infinity.
// Both use uniform grids, so a query costs a few element tests whatever the mesh size.
// Units: m.
#include "dem/core/types.h"
#include <array>
#include <limits>
#include <string>
#include <vector>

namespace dembridge::coupling
{
using dem::Vec3;
using Triangle = std::array<Vec3, 3>;
using Tetrahedron = std::array<Vec3, 4>;

/// Lists items (by index) in the cells of a uniform grid over a box.
class UniformGrid
{
public:
  UniformGrid() = default;
  /// A grid over [lo, hi] with cells of about @p cell_size (at most 128 per axis).
  UniformGrid(const Vec3& lo, const Vec3& hi, double cell_size);
  /// Lists item @p index in every cell that the box [lo, hi] overlaps.
  void insert(int index, const Vec3& lo, const Vec3& hi);
  /// The items listed in the cell of @p x (empty outside the grid).
  const std::vector<int>& items_at(const Vec3& x) const;

private:
  std::array<int, 3> cell_of(const Vec3& x) const;
  Vec3 lo_ = Vec3::Zero(), inverse_size_ = Vec3::Ones();
  std::array<int, 3> n_{{0, 0, 0}};
  std::vector<std::vector<int>> cells_;
  std::vector<int> none_;
};

class RegionVolume
{
public:
  RegionVolume() = default;
  /// From the volume's tetrahedra and its boundary triangles. Throws std::runtime_error if the
  /// volume is empty.
  RegionVolume(std::vector<Tetrahedron> tetrahedra, std::vector<Triangle> boundary,
               const std::string& key);

  bool contains(const Vec3& x) const;
  const Vec3& lo() const { return lo_; } ///< bounding box, m
  const Vec3& hi() const { return hi_; }
  double volume() const { return volume_; } ///< m^3
  const std::vector<Triangle>& boundary() const { return boundary_; }
  std::size_t n_tetrahedra() const { return tets_.size(); }

private:
  std::vector<Tetrahedron> tets_;
  /// per tetrahedron the inverse of [v1 - v0, v2 - v0, v3 - v0]: barycentric coordinates
  std::vector<Eigen::Matrix3d> to_barycentric_;
  std::vector<Triangle> boundary_;
  Vec3 lo_ = Vec3::Zero(), hi_ = Vec3::Zero();
  double volume_ = 0;
  UniformGrid grid_;
};

/// The volume of a gmsh mesh (.msh 2.2 or 4.1; tetrahedra or hexahedra), checked as FE meshes
/// are (fem/mesh.h) before deal.II reads it. Throws std::runtime_error naming @p key and the file.
RegionVolume read_region_volume(const std::string& file, const std::string& key);

class SurfaceDistance
{
public:
  SurfaceDistance() = default;
  SurfaceDistance(std::vector<Triangle> triangles, double reach);
  /// Distance to the nearest triangle if it is within the reach, else +infinity.
  double distance(const Vec3& x) const;
  std::size_t size() const { return triangles_.size(); }

private:
  std::vector<Triangle> triangles_;
  double reach_ = 0;
  UniformGrid grid_;
};

/// Distance from @p x to the triangle (a, b, c) (Ericson 2005, 5.1.5).
double point_triangle_distance(const Vec3& x, const Triangle& t);
} // namespace dembridge::coupling
