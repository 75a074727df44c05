#include "coupling/adaptive_region.h"
#include "fem/explicit_dynamics.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dembridge::coupling
{
using namespace dealii;

namespace
{
const std::string where = "Coupling/Adaptive region/";

std::string text(const Vec3& v)
{
  std::ostringstream s;
  s << v.x() << ", " << v.y() << ", " << v.z();
  return s.str();
}

/// Distance from x to the nearest of the ascending @p lines.
double to_nearest_line(const std::vector<double>& lines, double x)
{
  const auto it = std::lower_bound(lines.begin(), lines.end(), x);
  double d = std::numeric_limits<double>::infinity();
  if (it != lines.end())
    d = std::min(d, *it - x);
  if (it != lines.begin())
    d = std::min(d, x - *std::prev(it));
  return d;
}
} // namespace

AdaptiveRegion::AdaptiveRegion(const AdaptiveRegionSettings& settings, const GridLines& lines,
                               const HandshakeGeometry& g, PackingStrength strength,
                               std::vector<Vec3> packing, const double spacing)
    : settings_(settings), lines_(lines), geometry_(g), strength_(std::move(strength)),
      packing_(std::move(packing)), spacing_(spacing)
{
  check_settings();
  const double h = lay_out_cells();
  require_whole_particles_in_cells();
  // n = ceil(L / h - 1/2) (strictly deeper than L), plus the layers ahead
  layers_ = int(std::floor(g.band_width / h - 0.5 + 1e-9)) + 1 + settings_.layers_ahead;
  // a coarser cell than the band's reach would straddle the band's inner edge (the band's depth
  // along a coarse axis is the distance to faces of other orientations only when the faces
  // normal to it are at least L away)
  const int band_cells = int(std::ceil(g.band_width / h - 1e-9));
  if (settings_.fine_margin > 0 && settings_.fine_margin < band_cells)
    throw std::runtime_error(where + "fine margin: " + std::to_string(settings_.fine_margin) +
                             " cells is less than the band's depth (" + std::to_string(band_cells) +
                             " cells of the band element size)");
  // 0: the whole envelope along an axis with a face (no refinement under load: file comment)
  margin_ = settings_.fine_margin > 0 ? settings_.fine_margin : std::numeric_limits<int>::max() / 4;
  index_packing();
  find_envelope_lines();
  lay_out_averaging();
}

GridLines AdaptiveRegion::envelope_grid(const HandshakeGeometry& g, const Vec3& envelope_lo,
                                        const Vec3& envelope_hi, const Vec3& element_size,
                                        const double h, const Vec3& far_element_size,
                                        const double growth)
{
  GridLines planes;
  for (int d = 0; d < 3; ++d)
    planes[d] = {envelope_lo[d], envelope_hi[d]};
  return grid_lines(g.domain_lo,
                    coupled_mesh_steps(g, planes, element_size, h, far_element_size, growth));
}

// The grid lines of the envelope's faces.
void AdaptiveRegion::find_envelope_lines()
{
  for (int d = 0; d < 3; ++d)
  {
    const auto& l = lines_[d];
    auto nearest = [&](double x)
    {
      int best = 0;
      for (int i = 1; i < int(l.size()); ++i)
        if (std::abs(l[i] - x) < std::abs(l[best] - x))
          best = i;
      return best;
    };
    envelope_first_[d] = nearest(settings_.envelope_lo[d]);
    envelope_last_[d] = nearest(settings_.envelope_hi[d]);
  }
}

void AdaptiveRegion::widen_fine_zone()
{
  const int k = std::max(1, settings_.envelope_coarsening);
  for (int d = 0; d < 3; ++d)
  {
    // the region's faces normal to d between a region cell and a grid cell outside it
    int first = std::numeric_limits<int>::max(), last = std::numeric_limits<int>::min();
    for (std::size_t c = 0; c < region_.size(); ++c)
    {
      if (!region_[c])
        continue;
      int at[3] = {int(c % n_[0]), int((c / n_[0]) % n_[1]), int(c / (std::size_t(n_[0]) * n_[1]))};
      for (const int side : {-1, 1})
      {
        int next[3] = {at[0], at[1], at[2]};
        next[d] += side;
        if (next[d] < 0 || next[d] >= n_[d] || region_[cell_index(next[0], next[1], next[2])])
          continue;
        const int face = at[d] + (side > 0 ? 1 : 0);
        first = std::min(first, face), last = std::max(last, face);
      }
    }
    if (first > last)
      continue;
    const int e0 = envelope_first_[d], e1 = envelope_last_[d];
    // m cells either side, out to the coarse lines (every k-th from the envelope's lower face)
    first = e0 + ((std::max(e0, first - margin_) - e0) / k) * k;
    last = std::min(e1, e0 + ((std::min(e1, last + margin_) - e0 + k - 1) / k) * k);
    auto& z = fine_zone_;
    if (z[0][d] > z[1][d])
      z[0][d] = first, z[1][d] = last;
    else
      z[0][d] = std::min(z[0][d], first), z[1][d] = std::max(z[1][d], last);
  }
}

GridLines AdaptiveRegion::fe_lines() const
{
  const int k = std::max(1, settings_.envelope_coarsening);
  GridLines fe;
  for (int d = 0; d < 3; ++d)
  {
    const int e0 = envelope_first_[d], e1 = envelope_last_[d];
    for (int i = 0; i < int(lines_[d].size()); ++i)
    {
      const bool outside = i <= e0 || i >= e1;
      const bool coarse = (i - e0) % k == 0;
      const bool fine = i >= fine_zone_[0][d] && i <= fine_zone_[1][d];
      if (outside || coarse || fine)
        fe[d].push_back(lines_[d][i]);
    }
  }
  return fe;
}

// The settings' ranges, their defaults from the geometry (averaging radius, envelope), the
// bonds' strength.
void AdaptiveRegion::check_settings()
{
  auto& s = settings_;
  const auto& g = geometry_;
  if (!(s.threshold > 0 && s.threshold <= 1))
  {
    std::ostringstream m;
    m << where << "threshold: " << s.threshold
      << " lies outside (0, 1] (the share of the particle model's strength at which the "
         "continuum turns into particles)";
    throw std::runtime_error(m.str());
  }
  if (!(s.band_threshold > 0 && s.band_threshold <= 1))
  {
    std::ostringstream m;
    m << where << "band threshold: " << s.band_threshold << " lies outside (0, 1]";
    throw std::runtime_error(m.str());
  }
  if (!(s.averaging_radius >= 0))
    throw std::runtime_error(where + "averaging radius: must not be negative");
  if (s.averaging_radius == 0)
    s.averaging_radius = g.band_width;
  if (s.layers_ahead < 0)
    throw std::runtime_error(where + "layers ahead: must not be negative");
  if (!s.envelope_given)
    s.envelope_lo = g.domain_lo, s.envelope_hi = g.domain_hi;
  const double tol = 1e-9 * (g.domain_hi - g.domain_lo).norm();
  if ((s.envelope_lo - g.domain_lo).minCoeff() < -tol ||
      (g.domain_hi - s.envelope_hi).minCoeff() < -tol ||
      !((s.envelope_hi - s.envelope_lo).minCoeff() > 0))
    throw std::runtime_error(where + "envelope lower: the envelope (" + text(s.envelope_lo) +
                             " to " + text(s.envelope_hi) +
                             ") is empty or lies outside the FE domain (" + text(g.domain_lo) +
                             " to " + text(g.domain_hi) + ")");
  if (!(strength_.tensile_strength > 0))
    throw std::runtime_error(where + "enabled: the particle model has no bond strengths to "
                                     "grow against (set Damage/failure and its strengths)");
}

// The grid's cells, their volumes and which lie in the envelope; returns the smallest cell size
// in the envelope, m.
double AdaptiveRegion::lay_out_cells()
{
  const auto& s = settings_;
  for (int d = 0; d < 3; ++d)
    n_[d] = int(lines_[d].size()) - 1;
  const std::size_t n = std::size_t(n_[0]) * n_[1] * n_[2];
  cell_volume_.resize(n);
  envelope_.assign(n, 0);
  region_.assign(n, 0);
  continuum_.assign(n, 1);
  anchored_.assign(n, 0);
  utilisation_.assign(n, 0.f);
  averaged_.assign(n, 0.f);
  bond_marked_.assign(n, 0);
  double h = std::numeric_limits<double>::infinity();
  for (int k = 0; k < n_[2]; ++k)
    for (int j = 0; j < n_[1]; ++j)
      for (int i = 0; i < n_[0]; ++i)
      {
        const std::size_t c = cell_index(i, j, k);
        const Vec3 size(lines_[0][i + 1] - lines_[0][i], lines_[1][j + 1] - lines_[1][j],
                        lines_[2][k + 1] - lines_[2][k]);
        cell_volume_[c] = size.prod();
        const Vec3 x = centre(c);
        const bool inside =
            (x - s.envelope_lo).minCoeff() > 0 && (s.envelope_hi - x).minCoeff() > 0;
        envelope_[c] = inside;
        if (inside)
          h = std::min(h, size.minCoeff());
      }
  return h;
}

// The cells hold whole particles: no centre of the packing on a cell face inside the envelope.
void AdaptiveRegion::require_whole_particles_in_cells() const
{
  for (const Vec3& x : packing_)
    for (int d = 0; d < 3; ++d)
      if (to_nearest_line(lines_[d], x[d]) < 1e-3 * spacing_)
      {
        std::ostringstream m;
        m << "Coupling/band element size: the cells of an adaptive region must hold whole "
             "particles, but the particle centre ("
          << text(x)
          << ") lies on a cell face: make the cell size a multiple of the particle spacing ("
          << spacing_ << " m) and the envelope's corners whole spacings from the domain's";
        throw std::runtime_error(m.str());
      }
}

// Each cell's count of packing centres; each centre's packing index by its position.
void AdaptiveRegion::index_packing()
{
  cell_particles_.assign(cell_volume_.size(), 0);
  for (std::size_t p = 0; p < packing_.size(); ++p)
  {
    const auto c = cell_of(packing_[p]);
    ++cell_particles_[cell_index(c[0], c[1], c[2])];
    packing_index_.emplace(key(packing_[p]), std::int32_t(p));
  }
}

std::array<std::int64_t, 3> AdaptiveRegion::key(const Vec3& x) const
{
  const double q = 1e-6 * spacing_;
  std::array<std::int64_t, 3> k{};
  for (int d = 0; d < 3; ++d)
    k[d] = std::llround((x[d] - geometry_.domain_lo[d]) / q);
  return k;
}

std::int32_t AdaptiveRegion::packing_index(const Vec3& x) const
{
  const auto it = packing_index_.find(key(x));
  return it == packing_index_.end() ? -1 : it->second;
}

std::array<int, 3> AdaptiveRegion::cell_of(const Vec3& x) const
{
  std::array<int, 3> c{};
  for (int d = 0; d < 3; ++d)
  {
    const auto& l = lines_[d];
    const long i = long(std::upper_bound(l.begin(), l.end(), x[d]) - l.begin()) - 1;
    c[d] = int(std::clamp(i, 0L, long(n_[d]) - 1));
  }
  return c;
}

Vec3 AdaptiveRegion::centre(const std::size_t c) const
{
  const std::size_t i = c % n_[0], j = (c / n_[0]) % n_[1], k = c / (std::size_t(n_[0]) * n_[1]);
  return {0.5 * (lines_[0][i] + lines_[0][i + 1]), 0.5 * (lines_[1][j] + lines_[1][j + 1]),
          0.5 * (lines_[2][k] + lines_[2][k + 1])};
}

void AdaptiveRegion::start_from_box(const Vec3& lo, const Vec3& hi, const std::string& key_name)
{
  const double tol = 1e-6 * spacing_;
  for (int d = 0; d < 3; ++d)
    if (to_nearest_line(lines_[d], lo[d]) > tol || to_nearest_line(lines_[d], hi[d]) > tol)
    {
      std::ostringstream m;
      m << key_name << ": an adaptive region starts from whole cells, but the particle box ("
        << text(lo) << " to " << text(hi) << ") has a face between the cell planes along "
        << "xyz"[d] << " (cells of Coupling/band element size from the envelope's corner "
        << text(settings_.envelope_lo) << ")";
      throw std::runtime_error(m.str());
    }
  std::size_t n = 0;
  for (std::size_t c = 0; c < region_.size(); ++c)
  {
    const Vec3 x = centre(c);
    region_[c] = (x - lo).minCoeff() > 0 && (hi - x).minCoeff() > 0;
    if (region_[c] && !envelope_[c])
      throw std::runtime_error(key_name + ": the particle box (" + text(lo) + " to " + text(hi) +
                               ") reaches outside the adaptive region's envelope (" +
                               text(settings_.envelope_lo) + " to " + text(settings_.envelope_hi) +
                               ")");
    n += region_[c];
  }
  if (n == 0)
    throw std::runtime_error(key_name + ": the particle box holds no whole cell");
}

void AdaptiveRegion::set_families(std::vector<BondFamily> families)
{
  if (families.empty())
    throw std::runtime_error(where + "enabled: the particle region has no bonds");
  strength_.families = std::move(families);
}

void AdaptiveRegion::set_cells(std::vector<char> cells)
{
  if (cells.size() != region_.size())
    throw std::runtime_error(where + "cells: " + std::to_string(cells.size()) +
                             " cells, the grid has " + std::to_string(region_.size()));
  region_ = std::move(cells);
}

std::shared_ptr<const RegionVolume> AdaptiveRegion::volume() const
{
  std::vector<Tetrahedron> tets;
  std::vector<Triangle> faces;
  for (int k = 0; k < n_[2]; ++k)
    for (int j = 0; j < n_[1]; ++j)
      for (int i = 0; i < n_[0]; ++i)
      {
        if (!region_[cell_index(i, j, k)])
          continue;
        const int at[3] = {i, j, k};
        auto vertex = [&](int bits)
        {
          Vec3 v;
          for (int d = 0; d < 3; ++d)
            v[d] = lines_[d][at[d] + ((bits >> d) & 1)];
          return v;
        };
        // Kuhn's six tetrahedra around the diagonal v0-v7
        const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        for (const auto& o : orders)
          tets.push_back(Tetrahedron{
              {vertex(0), vertex(1 << o[0]), vertex((1 << o[0]) | (1 << o[1])), vertex(7)}});
        // faces towards cells outside the region (or outside the grid), two triangles each
        for (int d = 0; d < 3; ++d)
          for (const int side : {0, 1})
          {
            int next[3] = {i, j, k};
            next[d] += side ? 1 : -1;
            const bool open =
                next[d] < 0 || next[d] >= n_[d] || !region_[cell_index(next[0], next[1], next[2])];
            if (!open)
              continue;
            const int a = (d + 1) % 3, b = (d + 2) % 3, base = side << d;
            const Vec3 v00 = vertex(base), v10 = vertex(base | (1 << a)),
                       v01 = vertex(base | (1 << b)), v11 = vertex(base | (1 << a) | (1 << b));
            faces.push_back(Triangle{{v00, v10, v11}});
            faces.push_back(Triangle{{v00, v11, v01}});
          }
      }
  return std::make_shared<const RegionVolume>(std::move(tets), std::move(faces), where + "cells");
}

bool AdaptiveRegion::in_cells(const std::vector<char>& cells, const Vec3& x) const
{
  const auto c = cell_of(x);
  return cells[cell_index(c[0], c[1], c[2])];
}

std::size_t AdaptiveRegion::n_region_cells() const
{
  return std::size_t(std::count(region_.begin(), region_.end(), 1));
}

std::size_t AdaptiveRegion::count_particles(const std::vector<char>& cells) const
{
  std::size_t n = 0;
  for (std::size_t c = 0; c < cells.size(); ++c)
    if (cells[c])
      n += cell_particles_[c];
  return n;
}

double AdaptiveRegion::averaged_utilisation(const Vec3& x) const
{
  const auto c = cell_of(x);
  return averaged_[cell_index(c[0], c[1], c[2])];
}

void AdaptiveRegion::measure(const fem::ExplicitDynamics& fe, const std::vector<Vec3>& marked)
{
  std::fill(continuum_.begin(), continuum_.end(), 0);
  bond_marked_.assign(continuum_.size(), 0);
  for (const Vec3& x : marked)
  {
    const auto c = cell_of(x);
    bond_marked_[cell_index(c[0], c[1], c[2])] = 1;
  }
  std::fill(utilisation_.begin(), utilisation_.end(), 0.f);
  anchored_.assign(continuum_.size(), 0);
  CoveredValues values;
  for (const auto& cell : fe.get_dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      measure_cell(fe, cell, values);
  average_utilisation();
  largest_utilisation_ = std::max(largest_utilisation_, max_utilisation_);
}

void AdaptiveRegion::measure_cell(const fem::ExplicitDynamics& fe,
                                  const DoFHandler<3>::active_cell_iterator& cell,
                                  CoveredValues& cache)
{
  // the grid cells it covers (an axis-aligned box: vertex 0 its lower corner, 7 its upper); in
  // the envelope they are equal, so that their centres in the unit cell depend on their counts
  const Point<3> lo = cell->vertex(0), hi = cell->vertex(7);
  const double inset = 1e-6 * spacing_;
  const auto first = cell_of(Vec3(lo[0], lo[1], lo[2]) + Vec3::Constant(inset));
  const auto last = cell_of(Vec3(hi[0], hi[1], hi[2]) - Vec3::Constant(inset));
  const std::array<int, 3> counts = {
      {last[0] - first[0] + 1, last[1] - first[1] + 1, last[2] - first[2] + 1}};
  auto& values = cache[counts];
  if (!values)
  {
    std::vector<Point<3>> centres;
    for (int k = 0; k < counts[2]; ++k)
      for (int j = 0; j < counts[1]; ++j)
        for (int i = 0; i < counts[0]; ++i)
          centres.emplace_back((i + 0.5) / counts[0], (j + 0.5) / counts[1], (k + 0.5) / counts[2]);
    const Quadrature<3> at(centres, std::vector<double>(centres.size(), 1.0 / centres.size()));
    values = std::make_unique<FEValues<3>>(fe.get_mapping(), fe.get_fe(), at, update_gradients);
  }
  values->reinit(cell);
  const unsigned int n = values->n_quadrature_points;
  std::vector<SymmetricTensor<2, 3>> strain(n);
  (*values)[FEValuesExtractors::Vector(0)].get_function_symmetric_gradients(fe.displacement(),
                                                                            strain);
  std::vector<types::global_dof_index> dofs(fe.get_fe().n_dofs_per_cell());
  cell->get_dof_indices(dofs);
  const auto& inverse_mass = fe.inverse_lumped_mass();
  bool anchored = false;
  for (const auto i : dofs)
    anchored = anchored || !(inverse_mass(i) > 0);
  unsigned int q = 0;
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i, ++q)
      {
        Eigen::Matrix3d eps;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            eps(a, b) = strain[q][a][b];
        const std::size_t c = cell_index(i, j, k);
        utilisation_[c] = float(utilisation(strength_, eps));
        continuum_[c] = 1;
        anchored_[c] = anchored_[c] || anchored;
      }
}

void AdaptiveRegion::visit_state(dem::StateArchive& a)
{
  dem::StateGroup group(a, "region");
  auto bytes = [&](const std::string& name, std::vector<char>& v)
  {
    std::vector<std::uint8_t> raw(v.begin(), v.end());
    a.io_sized(name, raw);
    v.assign(raw.begin(), raw.end());
  };
  auto floats = [&](const std::string& name, std::vector<float>& v)
  {
    std::vector<double> wide(v.begin(), v.end());
    a.io_sized(name, wide);
    v.assign(wide.begin(), wide.end());
  };
  bytes("cells", region_);
  bytes("continuum", continuum_);
  bytes("anchored", anchored_);
  bytes("bond_marked", bond_marked_);
  floats("utilisation", utilisation_);
  floats("averaged_utilisation", averaged_);
  a.io("max_utilisation", max_utilisation_);
  a.io("largest_utilisation", largest_utilisation_);
  std::vector<std::int32_t> zone;
  for (const auto& end : fine_zone_)
    zone.insert(zone.end(), end.begin(), end.end());
  a.io("fine_zone", zone);
  if (zone.size() != 6)
    throw dem::InputError(a.where() + "fine_zone: " + std::to_string(zone.size()) +
                          " numbers, not 6");
  for (int e = 0; e < 2; ++e)
    for (int d = 0; d < 3; ++d)
      fine_zone_[e][d] = zone[3 * e + d];
}

AdaptiveRegion::Proposal AdaptiveRegion::propose() const
{
  Proposal p;
  p.cells = region_;
  std::size_t n_continuum = 0;
  std::vector<std::size_t> marked;
  for (std::size_t c = 0; c < continuum_.size(); ++c)
    if (continuum_[c])
    {
      ++n_continuum;
      if (averaged_[c] >= settings_.threshold || bond_marked_[c])
        marked.push_back(c);
      p.marked_by_bonds += bond_marked_[c] && averaged_[c] < settings_.threshold;
    }
  p.marked = marked.size();
  if (marked.empty())
    return p;
  if (marked.size() == n_continuum)
  {
    p.kind = Proposal::Kind::whole_body;
    return p;
  }
  for (const std::size_t c : marked)
  {
    const int at[3] = {int(c % n_[0]), int((c / n_[0]) % n_[1]),
                       int(c / (std::size_t(n_[0]) * n_[1]))};
    int lo[3], hi[3];
    for (int d = 0; d < 3; ++d)
      lo[d] = std::max(0, at[d] - layers_), hi[d] = std::min(n_[d] - 1, at[d] + layers_);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          const std::size_t o = cell_index(i, j, k);
          if (envelope_[o] && !anchored_[o] && !p.cells[o])
            p.cells[o] = 1, ++p.cells_added;
        }
  }
  if (p.cells_added == 0)
    return p;
  if (std::count(p.cells.begin(), p.cells.end(), 1) == std::ptrdiff_t(p.cells.size()))
  {
    p.kind = Proposal::Kind::whole_body;
    return p;
  }
  p.particles = count_particles(p.cells);
  p.kind = settings_.maximum_particles > 0 && p.particles > settings_.maximum_particles
               ? Proposal::Kind::capped
               : Proposal::Kind::grow;
  return p;
}
} // namespace dembridge::coupling
