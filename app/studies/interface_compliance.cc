// A plane's normal and shear compliance on a one-plane specimen (see interface_compliance.h).
#include "app/studies/interface_compliance.h"
#include "dem/measurements/elasticity_tensor.h"
#include "dem/measurements/particle_stress.h"
#include "dem/model/groups.h"
#include "dem/solvers/static_solver.h"
#include <cmath>
#include <numbers>
#include <sstream>

namespace dembridge::app
{
using dem::Vec3;

namespace
{
double mean_diameter(const dem::ParticleStore& p)
{
  double sum = 0;
  for (double r : p.radius)
    sum += 2 * r;
  return sum / double(p.size());
}

/// Moves the boundary layer by E x plus +-J/2 on the plane's two sides, rotations held at 0,
/// and solves; the equilibrium is written into m.particles.
void load_and_solve(dem::Model& m, const Eigen::Matrix3d& E, const Vec3& n, double offset,
                    const Vec3& J)
{
  dem::ParticleStore& p = m.particles;
  const auto [lo, hi] = dem::reference_extent(p);
  const Vec3 centre = 0.5 * (lo + hi);
  dem::StaticSettings s;
  s.cg_tolerance = 1e-12;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& r = p.reference_position[i];
    const double band = 1.5 * p.radius[i] * (1 + 1e-9);
    if (!(((r - lo).array() <= band).any() || ((hi - r).array() <= band).any()))
      continue;
    dem::StaticSettings::PrescribedDisplacement d;
    d.index = int(i);
    d.dofs = 63; // translations and rotations
    d.value.head<3>() = E * (r - centre) + (n.dot(r) < offset ? -0.5 : 0.5) * J;
    s.prescribed.push_back(d);
  }
  dem::solve_static(m, s);
}

struct Core
{
  Vec3 lo, hi;
  double volume;
};

/// The elasticity measurement's core: ElasticityMeasurementSettings' margin in from the extent,
/// cut to whole periods, and moved by 1e-6 diameters: its faces can lie on a lattice's layers
/// (HCP along x: the margin 4 r from the extent lands on one), and a box of whole periods holds
/// its share of particles only if it takes the layer on one face and not the one on the other,
/// which round-off would otherwise decide (a layer too many: 6 % too much stress on a box of 16
/// layers).
Core core_of(const dem::ParticleStore& p, const Vec3& period)
{
  const auto [lo, hi] = dem::reference_extent(p);
  const double d = mean_diameter(p), margin = dem::ElasticityMeasurementSettings{}.core_margin * d;
  Core c{lo + Vec3::Constant(margin + 1e-6 * d), hi - Vec3::Constant(margin - 1e-6 * d), 0};
  for (int axis = 0; axis < 3; ++axis)
    if (period[axis] > 0)
      c.hi[axis] =
          c.lo[axis] + period[axis] * std::floor((c.hi[axis] - c.lo[axis]) / period[axis] + 1e-9);
  c.volume = (c.hi - c.lo).prod();
  return c;
}

/// Least-squares u = a + G (x - at) over the core's particles on one side of the plane, a
/// diameter clear of it; its u at `at`.
Vec3 side_fit(const dem::ParticleStore& p, const Core& core, const Vec3& n, double offset,
              double side, const Vec3& at)
{
  const double clear = mean_diameter(p);
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Matrix<double, 4, 3> rhs = Eigen::Matrix<double, 4, 3>::Zero();
  long count = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& x = p.reference_position[i];
    if (!((x.array() >= core.lo.array()).all() && (x.array() <= core.hi.array()).all()) ||
        side * (n.dot(x) - offset) < clear)
      continue;
    Eigen::Vector4d row;
    row << 1.0, x - at;
    normal += row * row.transpose();
    rhs += row * (p.position[i] - x).transpose();
    ++count;
  }
  if (count < 8)
    throw dem::InputError("plane compliance: the plane leaves fewer than 8 core particles on one "
                          "side (a larger specimen, or the plane through its middle)");
  return normal.ldlt().solve(rhs).row(0).transpose();
}

/// The jump across the plane at the core's centre, and the core's mean stress.
std::pair<Vec3, Eigen::Matrix3d> jump_and_stress(const dem::Model& m, const Vec3& n, double offset,
                                                 const Vec3& period)
{
  const dem::ParticleStore& p = m.particles;
  const Core core = core_of(p, period);
  const Vec3 centre = 0.5 * (core.lo + core.hi);
  const Vec3 at = centre + (offset - n.dot(centre)) * n;
  const Vec3 jump = side_fit(p, core, n, offset, 1.0, at) - side_fit(p, core, n, offset, -1.0, at);
  const dem::ParticleStresses ps = dem::particle_stresses(p, m.bonds);
  const Eigen::Matrix3d sigma = dem::rve_average(p, ps, core.lo, core.hi, core.volume);
  return {jump, 0.5 * (sigma + sigma.transpose())};
}

dem::CaseConfig one_plane(dem::CaseConfig c, const Vec3& n, double offset,
                          const dem::BondClassConfig& plane_bonds)
{
  c.microstructure = {};
  dem::WeakPlaneSet plane;
  plane.normal = n;
  plane.offsets = {offset};
  c.microstructure.weak_planes = plane;
  c.microstructure.weak_plane = plane_bonds;
  return c;
}
} // namespace

PlaneCompliance plane_compliance(const dem::CaseConfig& specimen, const Vec3& n, const Vec3& s,
                                 double offset, const dem::BondClassConfig& plane_bonds,
                                 const Vec3& period)
{
  dem::CaseConfig intact_config = specimen;
  intact_config.microstructure = {};
  const dem::Model intact_model = dem::build_model(intact_config);
  const dem::Model cut_model = dem::build_model(one_plane(specimen, n, offset, plane_bonds));
  const double e = 1e-4, probe = e * mean_diameter(intact_model.particles);
  auto in_plane = [&](const Vec3& j) { return Eigen::Vector2d(j.dot(n), j.dot(s)); };
  PlaneCompliance out;
  for (int mode = 0; mode < 2; ++mode)
  {
    const Eigen::Matrix3d E =
        mode == 0 ? Eigen::Matrix3d(e * n * n.transpose())
                  : Eigen::Matrix3d(0.5 * e * (n * s.transpose() + s * n.transpose()));
    dem::Model intact = intact_model;
    load_and_solve(intact, E, n, offset, Vec3::Zero());
    const Eigen::Vector2d j0 = in_plane(jump_and_stress(intact, n, offset, period).first);
    auto jump_with = [&](const Vec3& J)
    {
      dem::Model cut = cut_model;
      load_and_solve(cut, E, n, offset, J);
      return jump_and_stress(cut, n, offset, period);
    };
    const Eigen::Vector2d free = in_plane(jump_with(Vec3::Zero()).first);
    Eigen::Matrix2d M;
    M.col(0) = (in_plane(jump_with(probe * n).first) - free) / probe;
    M.col(1) = (in_plane(jump_with(probe * s).first) - free) / probe;
    const Eigen::Vector2d fixed = (Eigen::Matrix2d::Identity() - M).inverse() * (free - j0);
    const auto [j, sigma] = jump_with(fixed[0] * n + fixed[1] * s);
    const Eigen::Vector2d jump = in_plane(j) - j0;
    out.consistency = std::max(out.consistency, (jump - fixed).norm() / fixed.norm());
    if (mode == 0)
      out.normal = jump[0] / n.dot(sigma * n);
    else
      out.shear = jump[1] / s.dot(sigma * n);
  }
  return out;
}

PlaneComplianceMean mean_plane_compliance(const dem::CaseConfig& specimen, int axis,
                                          const dem::BondClassConfig& plane_bonds, int angles)
{
  const auto kind = specimen.particles.kind;
  const Vec3 period = dem::lattice_axis_periods(kind, specimen.particles.radius);
  const double range =
      kind == dem::ParticleSource::Kind::hcp && axis == 2 ? std::numbers::pi / 6 : std::numbers::pi;
  dem::CaseConfig intact = specimen;
  intact.microstructure = {};
  const dem::Model m = dem::build_model(intact);
  const auto [lo, hi] = dem::reference_extent(m.particles);
  const Vec3 centre = 0.5 * (lo + hi), a = Vec3::Unit(axis);
  const Vec3 u = Vec3::Unit((axis + 1) % 3), v = Vec3::Unit((axis + 2) % 3);
  const double shifts[2] = {0, 0.5 * mean_diameter(m.particles)};
  PlaneComplianceMean out;
  for (int k = 0; k < angles; ++k)
  {
    const double theta = (k + 0.5) / angles * range;
    const Vec3 n = std::cos(theta) * u + std::sin(theta) * v, s = a.cross(n);
    PlaneCompliance each;
    for (double shift : shifts)
    {
      const PlaneCompliance B =
          plane_compliance(specimen, n, s, n.dot(centre) + shift, plane_bonds, period);
      each.normal += 0.5 * B.normal, each.shear += 0.5 * B.shear;
      each.consistency = std::max(each.consistency, B.consistency);
    }
    out.angles.push_back(theta);
    out.each.push_back(each);
    out.mean.normal += each.normal / angles, out.mean.shear += each.shear / angles;
    out.mean.consistency = std::max(out.mean.consistency, each.consistency);
  }
  return out;
}
} // namespace dembridge::app
