#include "dem/microstructure/columnar_grains.h"
#include "dem/microstructure/keyed_random.h"
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <sstream>

namespace dembridge::dem
{
namespace
{
std::string number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

[[noreturn]] void fail(const std::string& key, const std::string& why)
{
  throw InputError("Microstructure/" + key + ": " + why);
}

/// Salts that keep the column, granular and c-axis streams of one node apart.
constexpr std::uint64_t column_salt = 0x636f6c756d6e0001ull, granular_salt = 0x6772616e0002ull;

/// Hexagonal lattice of eq. (1) in the plane (u, v) with its seeds over a node window.
class ColumnSeeds
{
public:
  ColumnSeeds(const ColumnarGrainsConfig& c, double ulo, double uhi, double vlo, double vhi)
      : a_(column_lattice_spacing(c.diameter)), h_(a_ * std::sqrt(3.0) / 2),
        reach_(a_ / std::sqrt(3.0) + 2 * c.jitter * a_)
  {
    // nodes whose seed can be the nearest to a point of the window
    j0_ = long(std::floor((vlo - reach_) / h_)) - 1;
    const long j1 = long(std::ceil((vhi + reach_) / h_)) + 1;
    i0_ = long(std::floor((ulo - reach_) / a_ - 0.5 * double(j1))) - 1;
    const long i1 = long(std::ceil((uhi + reach_) / a_ - 0.5 * double(j0_))) + 1;
    ni_ = i1 - i0_ + 1, nj_ = j1 - j0_ + 1;
    seeds_.resize(std::size_t(ni_ * nj_));
    for (long j = j0_; j <= j1; ++j)
      for (long i = i0_; i <= i1; ++i)
        seeds_[index(i, j)] = column_seed(c, i, j);
  }

  /// The node (i, j) whose seed is nearest (u, v); ties go to the first node in (j, i) order.
  std::pair<long, long> nearest(double u, double v) const
  {
    const long jb = std::max(j0_, long(std::floor((v - reach_) / h_)));
    const long je = std::min(j0_ + nj_ - 1, long(std::ceil((v + reach_) / h_)));
    double best = std::numeric_limits<double>::infinity();
    std::pair<long, long> at{0, 0};
    for (long j = jb; j <= je; ++j)
    {
      const long ib = std::max(i0_, long(std::floor((u - reach_) / a_ - 0.5 * double(j))));
      const long ie = std::min(i0_ + ni_ - 1, long(std::ceil((u + reach_) / a_ - 0.5 * double(j))));
      for (long i = ib; i <= ie; ++i)
      {
        const auto& s = seeds_[index(i, j)];
        const double d2 = (s[0] - u) * (s[0] - u) + (s[1] - v) * (s[1] - v);
        if (d2 < best)
          best = d2, at = {i, j};
      }
    }
    return at;
  }
  std::array<double, 2> seed(long i, long j) const { return seeds_[index(i, j)]; }

private:
  std::size_t index(long i, long j) const { return std::size_t((j - j0_) * ni_ + (i - i0_)); }
  double a_, h_, reach_;
  long i0_ = 0, j0_ = 0, ni_ = 0, nj_ = 0;
  std::vector<std::array<double, 2>> seeds_;
};

double granular_spacing(double diameter)
{
  return diameter * std::cbrt(std::numbers::pi / 6); // eq. (2)
}
} // namespace

double column_lattice_spacing(double diameter)
{
  return diameter * std::sqrt(std::numbers::pi / (2 * std::sqrt(3.0))); // eq. (1)
}

std::array<double, 2> column_seed(const ColumnarGrainsConfig& c, long i, long j)
{
  const double a = column_lattice_spacing(c.diameter);
  KeyedRandom rng(c.seed, column_salt, i, j);
  const double r = c.jitter * a * std::sqrt(rng.uniform()); // uniform in the disc
  const double t = 2 * std::numbers::pi * rng.uniform();
  return {a * (double(i) + 0.5 * double(j)) + r * std::cos(t),
          a * std::sqrt(3.0) / 2 * double(j) + r * std::sin(t)};
}

Vec3 granular_seed(const ColumnarGrainsConfig& c, long i, long j, long k)
{
  const double g = granular_spacing(c.granular_diameter);
  KeyedRandom rng(c.seed, granular_salt, i, j, k);
  const double r = 0.5 * g * std::cbrt(rng.uniform()); // uniform in the ball
  return g * Vec3(double(i), double(j), double(k)) + r * rng.unit_vector();
}

void ColumnarGrainsConfig::validate() const
{
  if (!enabled)
    return;
  if (axis < 0 || axis > 2)
    fail("column axis", "must be x, y or z");
  if (!(diameter > 0) || !std::isfinite(diameter))
    fail("column diameter",
         "columnar grains need a positive mean column diameter (got " + number(diameter) + " m)");
  if (!(jitter >= 0 && jitter <= 1))
    fail("column jitter", "must lie in [0, 1] (got " + number(jitter) + ")");
  if (c_axis_aligned)
  {
    const Vec3 e = Vec3::Unit(axis);
    if (!((c_axis_direction - c_axis_direction.dot(e) * e).norm() > 1e-9 * c_axis_direction.norm()))
      fail("c-axis direction", "must not be parallel to the column axis (the c-axis of a column "
                               "lies in the plane across it)");
    if (!(c_axis_spread >= 0 && c_axis_spread <= 180))
      fail("c-axis spread", "must lie in [0, 180] degrees (got " + number(c_axis_spread) + ")");
  }
  if (granular_thickness < 0)
    fail("granular layer thickness", "must not be negative");
  if (granular_thickness > 0 && !(granular_diameter > 0))
    fail("granular grain diameter", "a granular layer needs a positive grain diameter (got " +
                                        number(granular_diameter) + " m)");
}

GrainMap assign_grains(const std::vector<Vec3>& x, const std::vector<double>& radii,
                       const ColumnarGrainsConfig& c)
{
  c.validate();
  GrainMap map;
  const std::size_t n = x.size();
  if (!c.enabled || n == 0)
    return map;
  const int ax = c.axis, iu = (ax + 1) % 3, iv = (ax + 2) % 3;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double mean_radius = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    lo = lo.cwiseMin(x[i] - Vec3::Constant(radii[i]));
    hi = hi.cwiseMax(x[i] + Vec3::Constant(radii[i]));
    mean_radius += radii[i] / double(n);
  }
  const double particle_diameter = 2 * mean_radius;
  const double width = std::max(hi[iu] - lo[iu], hi[iv] - lo[iv]);
  if (c.diameter < 2 * particle_diameter)
    fail("column diameter", number(c.diameter) + " m is below two particle diameters (" +
                                number(2 * particle_diameter) +
                                " m): a column needs particles across it");
  if (c.diameter > width)
    fail("column diameter", number(c.diameter) +
                                " m is above the specimen's width across the "
                                "columns (" +
                                number(width) + " m): the specimen would hold one column");
  const double top = hi[ax];
  if (c.granular_thickness > 0)
  {
    if (c.granular_thickness >= hi[ax] - lo[ax])
      fail("granular layer thickness", number(c.granular_thickness) +
                                           " m leaves no column: the specimen is " +
                                           number(hi[ax] - lo[ax]) + " m along the column axis");
    if (c.granular_diameter < 2 * particle_diameter)
      fail("granular grain diameter", number(c.granular_diameter) +
                                          " m is below two particle diameters (" +
                                          number(2 * particle_diameter) + " m)");
  }
  auto granular = [&](std::size_t i) { return x[i][ax] > top - c.granular_thickness; };

  // columns: the nearest seed in the plane, by node
  const ColumnSeeds seeds(c, lo[iu], hi[iu], lo[iv], hi[iv]);
  std::vector<std::pair<long, long>> column_node(n); // (j, i), lattice order
  std::map<std::pair<long, long>, std::int32_t> column_ids;
  for (std::size_t i = 0; i < n; ++i)
    if (!granular(i))
    {
      const auto [ni, nj] = seeds.nearest(x[i][iu], x[i][iv]);
      column_node[i] = {nj, ni};
      column_ids.emplace(column_node[i], 0);
    }
  // granular grains: the nearest seed in space
  const double g = granular_spacing(c.granular_diameter);
  std::vector<std::array<long, 3>> granular_node(n); // (k, j, i)
  std::map<std::array<long, 3>, std::int32_t> granular_ids;
  if (c.granular_thickness > 0)
    for (std::size_t i = 0; i < n; ++i)
      if (granular(i))
      {
        const double reach = (std::sqrt(3.0) / 2 + 1) * g; // a node's cell and its offset
        long node_lo[3], node_hi[3];
        for (int d = 0; d < 3; ++d)
          node_lo[d] = long(std::floor((x[i][d] - reach) / g)),
          node_hi[d] = long(std::ceil((x[i][d] + reach) / g));
        double best = std::numeric_limits<double>::infinity();
        for (long kk = node_lo[2]; kk <= node_hi[2]; ++kk)
          for (long jj = node_lo[1]; jj <= node_hi[1]; ++jj)
            for (long ii = node_lo[0]; ii <= node_hi[0]; ++ii)
            {
              const double d2 = (granular_seed(c, ii, jj, kk) - x[i]).squaredNorm();
              if (d2 < best)
                best = d2, granular_node[i] = {kk, jj, ii};
            }
        granular_ids.emplace(granular_node[i], 0);
      }

  // compact ids: columns in lattice order, then granular grains; c-axes keyed by node
  const Vec3 eu = Vec3::Unit(iu), ev = Vec3::Unit(iv);
  double aligned_angle = 0;
  if (c.c_axis_aligned)
    aligned_angle = std::atan2(c.c_axis_direction.dot(ev), c.c_axis_direction.dot(eu));
  for (auto& [node, id] : column_ids)
  {
    id = std::int32_t(map.grains.size());
    const auto s = seeds.seed(node.second, node.first);
    Grain grain;
    grain.seed = s[0] * eu + s[1] * ev;
    KeyedRandom rng(c.seed, column_salt + 1, node.second, node.first);
    const double angle = c.c_axis_aligned ? aligned_angle + c.c_axis_spread * std::numbers::pi /
                                                                180 * rng.standard_normal()
                                          : std::numbers::pi * rng.uniform();
    grain.c_axis = std::cos(angle) * eu + std::sin(angle) * ev;
    map.grains.push_back(grain);
  }
  map.columns = map.grains.size();
  for (auto& [node, id] : granular_ids)
  {
    id = std::int32_t(map.grains.size());
    Grain grain;
    grain.granular = true;
    grain.seed = granular_seed(c, node[2], node[1], node[0]);
    KeyedRandom rng(c.seed, granular_salt + 1, node[2], node[1], node[0]);
    grain.c_axis = rng.unit_vector();
    map.grains.push_back(grain);
  }
  map.of_particle.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    map.of_particle[i] =
        granular(i) ? granular_ids.at(granular_node[i]) : column_ids.at(column_node[i]);
  return map;
}
} // namespace dembridge::dem
