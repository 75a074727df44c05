// The Young's modulus of a columnar specimen across its columns against the interface-compliance
// estimate (app/studies/column_tessellation.h)
//     1 / E_x = 1 / E + S_v (3 B_N + B_T) / 8,
// S_v the columns' boundary area per volume (voro++), B_N and B_T the normal and shear compliance
// of a grain-boundary plane of the same bonds, measured on a one-plane specimen; E the same
// packing without grains.
//
// B_N and B_T (m/Pa): the jump in displacement across the plane per unit traction on it,
// [u] = B_N (n . t) n + B_T (t - (n . t) n) with t = sigma n; positive for a plane softer than
// the packing. A block with one plane of grain-boundary bonds through its middle has its
// boundary layer (centres within 1.5 r of a face) moved by a uniform strain plus the plane's own
// jump on its two sides, rotations held at 0: normal mode, uniaxial strain along the normal n;
// shear mode, pure shear in n and the slip direction t. Linear fits u = a + G x of the
// displacements on each side (core particles a diameter or more from the plane) extrapolated to
// the plane give the jump; the same fits on the block without the plane (the same packing and
// strain) give the lattice's own share (its displacements are not affine near the held layer),
// which is subtracted. The traction is the core's mean stress (particle_stress.h) on n.
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
CaseConfig with_plane(CaseConfig c, const Vec3& normal, double offset, double boundary_youngs)
{
  WeakPlaneSet plane;
  plane.normal = normal;
  plane.offsets = {offset};
  c.microstructure.weak_planes = plane;
  c.microstructure.weak_plane = boundary_bonds(c, boundary_youngs);
  return c;
}

/// Solves the block with its boundary layer (centres within 1.5 r of a face) moved by the
/// uniform strain E plus the jump +-J/2 on the two sides of the plane n.x = offset, rotations
/// held at 0; the equilibrium is written into m.particles.
void load_and_solve(Model& m, const Eigen::Matrix3d& E, const Vec3& n, double offset, const Vec3& J)
{
  ParticleStore& p = m.particles;
  const auto [lo, hi] = reference_extent(p);
  const Vec3 centre = 0.5 * (lo + hi);
  StaticSettings s;
  s.cg_tolerance = 1e-12;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& r = p.reference_position[i];
    const double band = 1.5 * p.radius[i] * (1 + 1e-9);
    if (!(((r - lo).array() <= band).any() || ((hi - r).array() <= band).any()))
      continue;
    StaticSettings::PrescribedDisplacement d;
    d.index = int(i);
    d.dofs = 63;
    d.value.head<3>() = E * (r - centre) + (n.dot(r) < offset ? -0.5 : 0.5) * J;
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
/// the plane, at the core's centre on the plane) and the core's mean stress, after load_and_solve.
std::pair<Vec3, Eigen::Matrix3d> jump_and_stress(const Model& m, const Vec3& n, double offset,
                                                 const Vec3& period)
{
  const ParticleStore& p = m.particles;
  const Core core = core_of(p, period);
  const Vec3 centre = 0.5 * (core.lo + core.hi);
  const Vec3 at = centre + (offset - n.dot(centre)) * n;
  auto inside = [&](const Vec3& x)
  { return (x.array() >= core.lo.array()).all() && (x.array() <= core.hi.array()).all(); };
  const Vec3 below = fitted_displacement(
      p, at, at, [&](const Vec3& x) { return inside(x) && n.dot(x) < offset - 2 * radius; });
  const Vec3 above = fitted_displacement(
      p, at, at, [&](const Vec3& x) { return inside(x) && n.dot(x) > offset + 2 * radius; });
  const ParticleStresses ps = particle_stresses(p, m.bonds, StressTheory::small_strain);
  const Eigen::Matrix3d sigma = rve_average(p, ps, core.lo, core.hi, core.volume);
  return {above - below, 0.5 * (sigma + sigma.transpose())};
}

struct PlaneCompliance
{
  double normal = 0, shear = 0; ///< B_N, B_T (m/Pa)
};

/// B_N and B_T of the plane n.x = offset (n across the columns, slip t = z x n) of @p c's
/// packing, its bonds of Young's modulus @p boundary_youngs: normal mode E = e n n, shear mode
/// E = e (n t + t n) / 2. The boundary must jump as the plane does (else it holds the plane
/// back near its edges): the jump measured, J_out = J_0 + M J in the plane's (n, t) components,
/// is linear in the jump J put on the boundary, so three solves give the fixed point
/// J = (I - M)^-1 J_0, and a fourth solves at it. The intact block under the same strain gives
/// the fits' own jump (the lattice's, not the plane's), which is subtracted.
PlaneCompliance plane_compliance(const CaseConfig& c, const Vec3& n, double offset,
                                 double boundary_youngs, const Vec3& period)
{
  const double e = 1e-4, probe = e * 2 * radius;
  const Vec3 t = Vec3::UnitZ().cross(n);
  const Model intact_model = build_model(c);
  const Model cut_model = build_model(with_plane(c, n, offset, boundary_youngs));
  auto in_plane = [&](const Vec3& j) { return Eigen::Vector2d(j.dot(n), j.dot(t)); };
  PlaneCompliance out;
  for (int mode = 0; mode < 2; ++mode)
  {
    const Eigen::Matrix3d E =
        mode == 0 ? Eigen::Matrix3d(e * n * n.transpose())
                  : Eigen::Matrix3d(0.5 * e * (n * t.transpose() + t * n.transpose()));
    Model intact = intact_model;
    load_and_solve(intact, E, n, offset, Vec3::Zero());
    const Eigen::Vector2d j0 = in_plane(jump_and_stress(intact, n, offset, period).first);
    auto jump_with = [&](const Vec3& J)
    {
      Model cut = cut_model;
      load_and_solve(cut, E, n, offset, J);
      return jump_and_stress(cut, n, offset, period);
    };
    const Eigen::Vector2d free = in_plane(jump_with(Vec3::Zero()).first);
    Eigen::Matrix2d M;
    M.col(0) = (in_plane(jump_with(probe * n).first) - free) / probe;
    M.col(1) = (in_plane(jump_with(probe * t).first) - free) / probe;
    const Eigen::Vector2d fixed = (Eigen::Matrix2d::Identity() - M).inverse() * (free - j0);
    const auto [j, sigma] = jump_with(fixed[0] * n + fixed[1] * t);
    const Eigen::Vector2d jump = in_plane(j);
    if (mode == 0)
      out.normal = (jump[0] - j0[0]) / n.dot(sigma * n);
    else
      out.shear = (jump[1] - j0[1]) / t.dot(sigma * n);
  }
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
  const PlaneCompliance B = plane_compliance(c, Vec3::UnitX(), offset, boundary_youngs, period);
  const double normal = d * d * (1 / kb.kn - 1 / k.kn), shear = d * d * (1 / kb.ks - 1 / k.ks);
  std::cout << "simple cubic: B_N " << B.normal << " m/Pa (springs in series " << normal
            << "; relative error " << B.normal / normal - 1 << "), B_T " << B.shear << " (" << shear
            << "; " << B.shear / shear - 1 << ")\n";
  EXPECT_NEAR(B.normal / normal, 1, 1e-9);
  EXPECT_NEAR(B.shear / shear, 1, 1e-9);
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

namespace
{
/// B_N and B_T averaged over the directions of the planes across the columns (x-y). The HCP
/// lattice's six-fold symmetry about z and its mirror x -> -x make them even functions of the
/// normal's angle theta of period 60 degrees, so theta in [0, 30] degrees covers them: the
/// midpoints of @p angles equal steps, each plane through the block's middle and a radius off it
/// (where it cuts the lattice), a 0.06 x 0.06 x 0.03 m block.
PlaneCompliance orientation_mean(double boundary_youngs, int angles)
{
  const CaseConfig c = block(ParticleSource::Kind::hcp, Vec3(0.06, 0.06, 0.03));
  const Vec3 period = lattice_axis_periods(ParticleSource::Kind::hcp, radius);
  const Model m = build_model(c);
  const auto [lo, hi] = reference_extent(m.particles);
  const Vec3 centre = 0.5 * (lo + hi);
  PlaneCompliance mean;
  const std::vector<double> shifts = {0, radius};
  for (int k = 0; k < angles; ++k)
  {
    const double theta = (k + 0.5) / angles * std::numbers::pi / 6;
    const Vec3 n(std::cos(theta), std::sin(theta), 0);
    for (double shift : shifts)
    {
      const PlaneCompliance B =
          plane_compliance(c, n, n.dot(centre) + shift, boundary_youngs, period);
      std::cout << "  plane at " << theta * 180 / std::numbers::pi << " degrees, shift " << shift
                << " m: B_N " << B.normal << ", B_T " << B.shear << " m/Pa\n";
      mean.normal += B.normal / double(angles * shifts.size());
      mean.shear += B.shear / double(angles * shifts.size());
    }
  }
  return mean;
}

CaseConfig columnar(double boundary_youngs, unsigned long seed)
{
  CaseConfig c = block(ParticleSource::Kind::hcp, Vec3(0.1, 0.1, 0.03));
  auto& g = c.microstructure.grains;
  g.enabled = true;
  g.diameter = 12.5e-3;
  g.jitter = 0.5;
  g.seed = seed;
  c.microstructure.grain_boundary = boundary_bonds(c, boundary_youngs);
  return c;
}
} // namespace

// The columnar specimen of test_columnar_elasticity (HCP, 0.1 x 0.1 x 0.03 m, r = 2.5 mm, columns
// of 12.5 mm, jitter 0.5) with grain-boundary bonds half as stiff as the columns' (Young's
// modulus 2 GPa against 4 GPa): the boundaries then carry about 30 % of its compliance across
// the columns. For each of three seeds, E across the columns (the mean of E_x and E_y of the
// measured tensor) against the estimate with that specimen's own S_v (its measured core).
TEST(ColumnCompliance, YoungsModulusAcrossTheColumnsFollowsTheEstimate)
{
  const double boundary_youngs = youngs / 2;
  const PlaneCompliance B = orientation_mean(boundary_youngs, 4);
  std::cout << "one plane, mean over its directions: B_N " << B.normal << ", B_T " << B.shear
            << " m/Pa\n";
  EXPECT_GT(B.normal, 0);
  EXPECT_GT(B.shear, 0);

  ElasticityMeasurementSettings s;
  s.core_period = lattice_axis_periods(ParticleSource::Kind::hcp, radius);
  const Vec3 intact_E = measured_stiffness_tensor(
                            build_model(block(ParticleSource::Kind::hcp, Vec3(0.1, 0.1, 0.03))), s)
                            .properties.youngs_modulus;
  const double E = 0.5 * (intact_E[0] + intact_E[1]);
  std::cout << "without grains: E_x " << intact_E[0] / 1e9 << ", E_y " << intact_E[1] / 1e9
            << " GPa\n";
  for (unsigned long seed = 1; seed <= 3; ++seed)
  {
    const CaseConfig c = columnar(boundary_youngs, seed);
    const Model m = build_model(c);
    const MeasuredElasticity measured = measured_stiffness_tensor(m, s);
    const auto tessellation =
        column_tessellation(c.microstructure.grains, measured.core_lo, measured.core_hi);
    const double S_v = tessellation.boundary_area_per_volume;
    const double estimate = interface_compliance_youngs_modulus(E, S_v, B.normal, B.shear);
    const Vec3& Em = measured.properties.youngs_modulus;
    const double across = 0.5 * (Em[0] + Em[1]);
    std::cout << "seed " << seed << ": " << m.microstructure.columns << " columns, "
              << tessellation.cells << " reach into the core (its area that of "
              << tessellation.window_area / (std::numbers::pi * 12.5e-3 * 12.5e-3 / 4) << "); S_v "
              << S_v << " 1/m; E_x " << Em[0] / 1e9 << ", E_y " << Em[1] / 1e9 << " GPa; estimate "
              << estimate / 1e9 << " GPa; measured / estimate " << across / estimate << "\n";
    EXPECT_GE(tessellation.cells, 50);
    // In-plane isotropy (the full check, E(theta), C44 against C55 and C66 against
    // (C11 - C12) / 2 over six seeds, is test_columnar_elasticity's): within its 8 %.
    EXPECT_LT(std::abs(Em[0] - Em[1]) / across, 0.08);
    // The boundaries matter: E across the columns well below the intact E (measured 0.70).
    EXPECT_LT(across / E, 0.75);
    // The estimate (measured 0.955, 0.960, 0.962: the specimen is softer than the estimate; see
    // docs/microstructure.md for the trend with the boundaries' stiffness).
    EXPECT_NEAR(across / estimate, 1, 0.05);
  }
}
