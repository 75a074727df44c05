#include "coupling/region_volume.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dembridge::coupling
{
UniformGrid::UniformGrid(const Vec3& lo, const Vec3& hi, const double cell_size) : lo_(lo)
{
  for (int d = 0; d < 3; ++d)
  {
    const double length = std::max(hi[d] - lo[d], 1e-300);
    n_[d] = int(std::clamp(std::ceil(length / cell_size), 1.0, 128.0)); // in double: no overflow
    inverse_size_[d] = n_[d] / length;
  }
  cells_.resize(std::size_t(n_[0]) * n_[1] * n_[2]);
}

std::array<int, 3> UniformGrid::cell_of(const Vec3& x) const
{
  std::array<int, 3> c{};
  for (int d = 0; d < 3; ++d) // clamped to one cell beyond either end before the cast
    c[d] = int(std::clamp(std::floor((x[d] - lo_[d]) * inverse_size_[d]), -1.0, double(n_[d])));
  return c;
}

void UniformGrid::insert(const int index, const Vec3& lo, const Vec3& hi)
{
  auto a = cell_of(lo), b = cell_of(hi);
  for (int d = 0; d < 3; ++d)
  {
    a[d] = std::max(a[d], 0);
    b[d] = std::min(b[d], n_[d] - 1);
    if (a[d] > b[d])
      return;
  }
  for (int k = a[2]; k <= b[2]; ++k)
    for (int j = a[1]; j <= b[1]; ++j)
      for (int i = a[0]; i <= b[0]; ++i)
        cells_[(std::size_t(k) * n_[1] + j) * n_[0] + i].push_back(index);
}

const std::vector<int>& UniformGrid::items_at(const Vec3& x) const
{
  const auto c = cell_of(x);
  for (int d = 0; d < 3; ++d)
    if (c[d] < 0 || c[d] >= n_[d])
      return none_;
  return cells_[(std::size_t(c[2]) * n_[1] + c[1]) * n_[0] + c[0]];
}

// ------------------------------------------------------------------------------------------
RegionVolume::RegionVolume(std::vector<Tetrahedron> tetrahedra, std::vector<Triangle> boundary,
                           const std::string& key)
    : tets_(std::move(tetrahedra)), boundary_(std::move(boundary))
{
  if (tets_.empty() || boundary_.empty())
    throw std::runtime_error(key + ": the mesh holds no volume (three-dimensional cells)");
  lo_ = hi_ = tets_[0][0];
  for (const auto& t : tets_)
  {
    for (const auto& v : t)
      lo_ = lo_.cwiseMin(v), hi_ = hi_.cwiseMax(v);
    volume_ += std::abs((t[1] - t[0]).cross(t[2] - t[0]).dot(t[3] - t[0])) / 6;
  }
  if (!(volume_ > 0))
    throw std::runtime_error(key + ": the mesh's volume is zero");
  to_barycentric_.reserve(tets_.size());
  for (const auto& t : tets_)
  {
    Eigen::Matrix3d J;
    J << t[1] - t[0], t[2] - t[0], t[3] - t[0];
    to_barycentric_.push_back(J.inverse()); // a flat one: not finite, left out of the grid
  }
  // cells of about two tetrahedron sizes: a few tetrahedra listed per cell
  const double size = 2 * std::cbrt(6 * volume_ / double(tets_.size()));
  grid_ = UniformGrid(lo_, hi_, size);
  for (std::size_t k = 0; k < tets_.size(); ++k)
  {
    if (!to_barycentric_[k].allFinite())
      continue;
    Vec3 a = tets_[k][0], b = tets_[k][0];
    for (const auto& v : tets_[k])
      a = a.cwiseMin(v), b = b.cwiseMax(v);
    const Vec3 grow = Vec3::Constant(1e-9 * (b - a).norm());
    grid_.insert(int(k), a - grow, b + grow);
  }
}

bool RegionVolume::contains(const Vec3& x) const
{
  for (const int k : grid_.items_at(x))
  {
    const Vec3 l = to_barycentric_[k] * (x - tets_[k][0]);
    const double tol = 1e-9;
    if (l.minCoeff() >= -tol && l.sum() <= 1 + tol)
      return true;
  }
  return false;
}

// ------------------------------------------------------------------------------------------
double point_triangle_distance(const Vec3& p, const Triangle& t)
{
  const Vec3 &a = t[0], &b = t[1], &c = t[2];
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
    return ap.norm(); // vertex a
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
    return bp.norm(); // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) // edge ab
    return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
    return cp.norm(); // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) // edge ac
    return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) // edge bc
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denominator = 1 / (va + vb + vc); // inside the face
  return (p - (a + ab * (vb * denominator) + ac * (vc * denominator))).norm();
}

SurfaceDistance::SurfaceDistance(std::vector<Triangle> triangles, const double reach)
    : triangles_(std::move(triangles)), reach_(reach)
{
  if (triangles_.empty())
    return;
  Vec3 lo = triangles_[0][0], hi = lo;
  double edges = 0;
  for (const auto& t : triangles_)
    for (int v = 0; v < 3; ++v)
    {
      lo = lo.cwiseMin(t[v]), hi = hi.cwiseMax(t[v]);
      edges += (t[(v + 1) % 3] - t[v]).norm();
    }
  const Vec3 grow = Vec3::Constant(reach_ * (1 + 1e-9));
  // cells of at least the reach (a triangle is listed in a few of them), at most 128 per axis
  const double size = std::max(reach_, edges / (3.0 * double(triangles_.size())));
  grid_ = UniformGrid(lo - grow, hi + grow, size);
  for (std::size_t k = 0; k < triangles_.size(); ++k)
  {
    const auto& t = triangles_[k];
    const Vec3 a = t[0].cwiseMin(t[1]).cwiseMin(t[2]), b = t[0].cwiseMax(t[1]).cwiseMax(t[2]);
    grid_.insert(int(k), a - grow, b + grow);
  }
}

double SurfaceDistance::distance(const Vec3& x) const
{
  double nearest = std::numeric_limits<double>::infinity();
  for (const int k : grid_.items_at(x))
    nearest = std::min(nearest, point_triangle_distance(x, triangles_[k]));
  return nearest <= reach_ ? nearest : std::numeric_limits<double>::infinity();
}
} // namespace dembridge::coupling
