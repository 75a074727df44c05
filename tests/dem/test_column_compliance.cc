// The Young's modulus of a columnar specimen across its columns against the interface-compliance
// estimate (app/studies/column_tessellation.h)
//     1 / E_x = 1 / E + S_v (3 B_N + B_T) / 8,
// S_v the columns' boundary area per volume (voro++), B_N and B_T the normal and shear compliance
// of a grain-boundary plane of the same bonds, measured on a one-plane specimen; E the same
// packing without grains.
//
// B_N and B_T (m/Pa): the jump in displacement across the plane per unit traction on it. A block
// with one plane of grain-boundary bonds through its middle is loaded through its boundary layer
// (centres within 1.5 r of a face): normal mode, uniaxial strain across the plane (the boundary
// held in the plane's two directions, the faces parallel to the plane moved across it, the other
// faces free across it); shear mode, pure shear in the plane normal and the slip direction (the
// boundary moved affinely along the normal, the faces parallel to the plane also along the slip,
// the others free along it). Linear fits u = a + G x of the displacements on each side (particles
// of the core at least a diameter from the plane) extrapolated to the plane's centre give the
// jump; the same fits on the block without the plane (the same packing, the same loads) give its
// intact value, which is subtracted. The traction is the core's mean stress (particle_stress.h)
// on the plane's normal.
#include "app/studies/column_tessellation.h"
#include "dem/bonds/bond_model.h"
#include "dem/measurements/elasticity_tensor.h"
#include "dem/measurements/particle_stress.h"
#include "dem/model/groups.h"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <numbers>

using namespace dembridge::dem;
using dembridge::app::column_tessellation;
using dembridge::app::interface_compliance_youngs_modulus;

namespace
{
constexpr double radius = 2.5e-3, youngs = 4e9;

CaseConfig block(ParticleSource::Kind kind, const Vec3& size)
{
  CaseConfig c;
  c.particles.kind = kind;
  c.particles.radius = radius;
  c.particles.box_size = size;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = youngs;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.material.stiffness_ratio = 4.2;
  c.run.static_solver = true;
  return c;
}

BondClassConfig boundary_bonds(const CaseConfig& c, double boundary_youngs)
{
  BondClassConfig b = BondClassConfig::of_specimen(c.bonds.material, c.damage);
  b.material.youngs_modulus = boundary_youngs;
  return b;
}

/// @p c with one weak plane n.x = offset whose bonds have the Young's modulus @p boundary_youngs.
CaseConfig with_plane(CaseConfig c, int normal_axis, double offset, double boundary_youngs)
{
  WeakPlaneSet plane;
  plane.normal = Vec3::Unit(normal_axis);
  plane.offsets = {offset};
  c.microstructure.weak_planes = plane;
  c.microstructure.weak_plane = boundary_bonds(c, boundary_youngs);
  return c;
}

enum class Mode
{
  normal,
  shear
};

/// Solves the block under the mode's boundary field (strain magnitude e; normal axis n, slip axis
/// t across the columns), written into m.particles. Shear: the faces normal to t carry the slip
/// field u_t = e x_n / 2 plus the jump +-J/2 on the plane's two sides (n.x = offset).
void load_and_solve(Model& m, Mode mode, int n, int t, double offset = 0, double jump = 0)
{
  const double e = 1e-4;
  ParticleStore& p = m.particles;
  const auto [lo, hi] = reference_extent(p);
  const Vec3 centre = 0.5 * (lo + hi);
  StaticSettings s;
  s.cg_tolerance = 1e-12;
  const int other = 3 - n - t;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& r = p.reference_position[i];
    const Vec3 x = r - centre;
    const double band = 1.5 * p.radius[i] * (1 + 1e-9);
    auto on_face = [&](int axis)
    { return r[axis] - lo[axis] <= band || hi[axis] - r[axis] <= band; };
    if (!(on_face(0) || on_face(1) || on_face(2)))
      continue;
    StaticSettings::PrescribedDisplacement d;
    d.index = int(i);
    d.dofs = std::uint8_t((1u << other) | dof_rx | dof_ry | dof_rz); // rotations held at 0
    if (mode == Mode::normal)
    {
      d.dofs |= std::uint8_t(1u << t);
      if (on_face(n))
        d.dofs |= std::uint8_t(1u << n), d.value[n] = e * x[n];
    }
    else
    {
      d.dofs |= std::uint8_t(1u << n), d.value[n] = 0.5 * e * x[t];
      if (on_face(n) || on_face(t))
        d.dofs |= std::uint8_t(1u << t),
            d.value[t] = 0.5 * e * x[n] + (r[n] < offset ? -0.5 : 0.5) * jump;
    }
    s.prescribed.push_back(d);
  }
  const StaticResult r = solve_static(m, s);
  EXPECT_LT(r.residual, 1e-9);
}

/// Least-squares u = a + G (x - c) over the particles selected; returns the fit's u at @p at.
template <class Select>
Vec3 fitted_displacement(const ParticleStore& p, const Vec3& c, const Vec3& at, Select select)
{
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Matrix<double, 4, 3> rhs = Eigen::Matrix<double, 4, 3>::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& x = p.reference_position[i];
    if (!select(x))
      continue;
    Eigen::Vector4d row;
    row << 1.0, x - c;
    normal += row * row.transpose();
    rhs += row * (p.position[i] - x).transpose();
  }
  const Eigen::Matrix<double, 4, 3> coef = normal.ldlt().solve(rhs);
  Eigen::Vector4d row;
  row << 1.0, at - c;
  return coef.transpose() * row;
}

struct Core
{
  Vec3 lo, hi;
  double volume;
};

/// The elasticity measurement's core: two diameters in from the extent, cut to whole periods.
Core core_of(const ParticleStore& p, const Vec3& period)
{
  auto [lo, hi] = reference_extent(p);
  Core c{lo + Vec3::Constant(4 * radius), hi - Vec3::Constant(4 * radius), 0};
  for (int d = 0; d < 3; ++d)
    if (period[d] > 0)
      c.hi[d] = c.lo[d] + period[d] * std::floor((c.hi[d] - c.lo[d]) / period[d] + 1e-9);
  c.volume = (c.hi - c.lo).prod();
  return c;
}

/// The jump across the plane n.x = offset (fits on the core's two sides, a diameter clear of
/// the plane) and the core's mean stress, after load_and_solve.
std::pair<Vec3, Eigen::Matrix3d> jump_and_stress(const Model& m, int n, double offset,
                                                 const Vec3& period)
{
  const ParticleStore& p = m.particles;
  const Core core = core_of(p, period);
  Vec3 at = 0.5 * (core.lo + core.hi);
  at[n] = offset;
  auto inside = [&](const Vec3& x)
  { return (x.array() >= core.lo.array()).all() && (x.array() <= core.hi.array()).all(); };
  const Vec3 below = fitted_displacement(
      p, at, at, [&](const Vec3& x) { return inside(x) && x[n] < offset - 2 * radius; });
  const Vec3 above = fitted_displacement(
      p, at, at, [&](const Vec3& x) { return inside(x) && x[n] > offset + 2 * radius; });
  const ParticleStresses ps = particle_stresses(p, m.bonds, StressTheory::small_strain);
  return {above - below, rve_average(p, ps, core.lo, core.hi, core.volume)};
}

struct PlaneCompliance
{
  double normal = 0, shear = 0; ///< B_N, B_T (m/Pa)
};

/// B_N and B_T of the plane n.x = offset of @p c's packing (slip along t), its bonds of Young's
/// modulus @p boundary_youngs. In shear the faces normal to t must slip by the plane's own jump
/// J (else their rows, short of bonds on one side, hold the plane back): J_out(J) is linear in
/// the jump J put on them, J_out = J_0 + s J, so two solves give the fixed point
/// J = J_0 / (1 - s), and a third solves at it.
PlaneCompliance plane_compliance(const CaseConfig& c, int n, int t, double offset,
                                 double boundary_youngs, const Vec3& period)
{
  PlaneCompliance out;
  const Model intact_model = build_model(c);
  const Model cut_model = build_model(with_plane(c, n, offset, boundary_youngs));
  Model intact = intact_model, cut = cut_model;
  load_and_solve(intact, Mode::normal, n, t);
  load_and_solve(cut, Mode::normal, n, t);
  {
    const auto [j0, s0] = jump_and_stress(intact, n, offset, period);
    const auto [j, s] = jump_and_stress(cut, n, offset, period);
    out.normal = (j[n] - j0[n]) / s(n, n);
  }
  intact = intact_model;
  load_and_solve(intact, Mode::shear, n, t);
  const Vec3 j0 = jump_and_stress(intact, n, offset, period).first;
  load_and_solve(cut, Mode::shear, n, t, offset, 0);
  const double first = jump_and_stress(cut, n, offset, period).first[t];
  cut = cut_model;
  load_and_solve(cut, Mode::shear, n, t, offset, first);
  const double second = jump_and_stress(cut, n, offset, period).first[t];
  const double slope = (second - first) / first, fixed = first / (1 - slope);
  cut = cut_model;
  load_and_solve(cut, Mode::shear, n, t, offset, fixed);
  const auto [j, s] = jump_and_stress(cut, n, offset, period);
  EXPECT_NEAR(j[t] / fixed, 1, 1e-6); // the faces slip with the plane
  out.shear = (j[t] - j0[t]) / (0.5 * (s(n, t) + s(t, n)));
  return out;
}
} // namespace

// The definition on the simple cubic lattice, where it is exact: each bond across the plane
// carries the traction on its cell's face d^2 in series with the chain, so the plane adds
// d^2 (1/k_plane - 1/k) per unit traction, normal (k_n) and in shear (k_s; the particles turn
// with the body, the shear springs alone take the slip).
TEST(PlaneCompliance, SimpleCubicPlaneIsSpringsInSeries)
{
  const CaseConfig c = block(ParticleSource::Kind::cubic, Vec3(0.08, 0.05, 0.03));
  const double d = 2 * radius, boundary_youngs = youngs / 3;
  const BondStiffness k = bond_stiffness(c.bonds.material, d, radius, radius);
  BondMaterial soft = c.bonds.material;
  soft.youngs_modulus = boundary_youngs;
  const BondStiffness kb = bond_stiffness(soft, d, radius, radius);
  const Vec3 period = lattice_axis_periods(ParticleSource::Kind::cubic, radius);
  const double offset = std::round(c.particles.box_size[0] / d / 2) * d; // layer centres at r + d i
  const PlaneCompliance B = plane_compliance(c, 0, 1, offset, boundary_youngs, period);
  const double normal = d * d * (1 / kb.kn - 1 / k.kn), shear = d * d * (1 / kb.ks - 1 / k.ks);
  std::cout << "simple cubic: B_N " << B.normal << " (springs in series " << normal << "), B_T "
            << B.shear << " (" << shear << ") m/Pa\n";
  EXPECT_NEAR(B.normal / normal, 1, 1e-6);
  EXPECT_NEAR(B.shear / shear, 1, 1e-6);
}

// A regular honeycomb (jitter 0) of lattice spacing a has boundary length 2/a per area (each
// hexagon of side a/sqrt3 owns half its perimeter, 3 a / sqrt3, on the area sqrt3 a^2 / 2); a
// window of whole rectangular periods (a by sqrt3 a; its sides on no edge: a quarter period off
// the seeds along u, where rows alternate edges at whole and half periods) holds exactly that.
TEST(ColumnTessellation, HoneycombBoundaryLengthPerArea)
{
  ColumnarGrainsConfig g;
  g.enabled = true;
  g.diameter = 12.5e-3;
  g.jitter = 0;
  const double a = column_lattice_spacing(g.diameter);
  const auto t =
      column_tessellation(g, Vec3(a / 4, 0, 0), Vec3(7.25 * a, 4 * std::sqrt(3.0) * a, 1));
  std::cout << "honeycomb: S_v a = " << t.boundary_area_per_volume * a << " over " << t.cells
            << " cells\n";
  EXPECT_NEAR(t.boundary_area_per_volume * a, 2.0, 1e-9);
}
