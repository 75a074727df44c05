#include "dem/measurements/measurements.h"
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace dembridge::dem
{
namespace
{
Vec3 reference_centroid(const ParticleStore& p, const Group& g)
{
  Vec3 c = Vec3::Zero();
  for (int i : g.members)
    c += p.reference_position[i];
  return c / double(g.members.size());
}
/// Eq. 65's lateral strain along d from the bounding particles of the two faces normal to d,
/// as the slope du_d/dx_d of the least-squares plane u_d = a + c . X through both groups
/// (reference positions X). For faces whose particles share their mean positions this is
/// exactly (mean u_d(high) - mean u_d(low)) / width; the other two slopes absorb a rigid
/// rotation (and shear), which otherwise leaks into the ratio when the two faces' particles
/// sit at different mean heights (HCP layers).
double lateral_strain(const ParticleStore& p, const Group& low, const Group& high, int d)
{
  // centred normal equations: cov c = b, cov = sum (X - Xm)(X - Xm)^T, b = sum (X - Xm) u_d
  Vec3 mean = Vec3::Zero();
  double n = 0;
  for (const Group* g : {&low, &high})
    for (int i : g->members)
      mean += p.reference_position[i], n += 1;
  mean /= n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  Vec3 rhs = Vec3::Zero();
  for (const Group* g : {&low, &high})
    for (int i : g->members)
    {
      const Vec3 x = p.reference_position[i] - mean;
      cov += x * x.transpose();
      rhs += x * (p.position[i][d] - p.reference_position[i][d]);
    }
  // A face group whose particles all share a coordinate leaves that slope undetermined: the
  // pseudo-inverse drops the degenerate directions and keeps the determined ones.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const double cutoff = 1e-12 * eig.eigenvalues().maxCoeff();
  Vec3 c = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
    if (eig.eigenvalues()[k] > cutoff)
      c += eig.eigenvectors().col(k) * (eig.eigenvectors().col(k).dot(rhs) / eig.eigenvalues()[k]);
  return c[d];
}
} // namespace

AxialResponse axial_response(const ParticleStore& p, const Group& fixed_end,
                             const Group& loaded_end, int axis, double section_area)
{
  AxialResponse r;
  r.axis = axis;
  const auto [lo, hi] = reference_extent(p);
  const Vec3 extent = hi - lo;
  r.area = 1.0;
  for (int d = 0; d < 3; ++d)
    if (d != axis)
      r.area *= extent[d];
  if (section_area > 0)
    r.area = section_area;
  const double dx =
      reference_centroid(p, loaded_end)[axis] - reference_centroid(p, fixed_end)[axis];
  r.gauge_length = std::abs(dx);
  if (!(r.gauge_length > 0))
    throw InputError("Measurements/modulus groups: the two end groups have the same position");
  const double du = mean_displacement(p, loaded_end)[axis] - mean_displacement(p, fixed_end)[axis];
  r.strain = du / dx; // dx carries the orientation: tension positive
  // The load on the loaded end, oriented like dx (a pull on the + end is tension): its support
  // reaction when its motion is prescribed; under force control its net force vanishes in
  // equilibrium, so the fixed end's reaction (equal and opposite) measures the load instead.
  bool prescribed = false;
  for (int i : loaded_end.members)
    prescribed = prescribed || (p.dof_mask[i] & (1u << axis));
  const double load =
      prescribed ? total_force(p, loaded_end)[axis] : -total_force(p, fixed_end)[axis];
  r.force = load * (dx > 0 ? 1.0 : -1.0);
  r.force_controlled = !prescribed;
  r.stress = r.force / r.area;
  r.youngs_modulus = r.strain != 0 ? r.stress / r.strain : 0.0;
  for (int d = 0; d < 3; ++d)
  {
    if (d == axis)
      continue;
    GroupSelection s;
    s.kind = GroupSelection::Kind::face;
    s.face_axis = d;
    s.face_upper = false;
    const Group low = select_group(p, "lateral-", s, "Measurements");
    s.face_upper = true;
    const Group high = select_group(p, "lateral+", s, "Measurements");
    const double width = reference_centroid(p, high)[d] - reference_centroid(p, low)[d];
    if (width > 0 && r.strain != 0)
      r.poisson_ratio[d] = -lateral_strain(p, low, high, d) / r.strain;
  }
  return r;
}

ModulusFit fit_youngs_modulus(const std::vector<double>& du, const std::vector<double>& force,
                              const AxialResponse& geometry)
{
  ModulusFit fit;
  double umax = 0;
  for (double u : du)
    umax = std::max(umax, std::abs(u));
  double su = 0, sf = 0, suu = 0, suf = 0;
  for (std::size_t k = 0; k < du.size() && k < force.size(); ++k)
    if (std::abs(du[k]) >= 0.25 * umax && umax > 0)
    {
      ++fit.points;
      su += du[k], sf += force[k], suu += du[k] * du[k], suf += du[k] * force[k];
    }
  const double n = double(fit.points), det = n * suu - su * su;
  if (fit.points < 2 || !(det > 0))
    return fit;
  const double slope = (n * suf - su * sf) / det; // N/m
  // stress/strain = (F_or / A) / (du / dx) with F_or = F sign(dx): slope |dx| / A
  fit.youngs_modulus = slope * geometry.gauge_length / geometry.area;
  return fit;
}
} // namespace dembridge::dem

namespace dembridge::dem
{
FlexuralResponse flexural_response(const ParticleStore& p, const Group& pin, const Group& roller,
                                   const Group& loaded, const Group& bottom, int span_axis,
                                   int load_axis, double nu, double fs)
{
  FlexuralResponse r;
  const auto [lo, hi] = reference_extent(p);
  const int width_axis = 3 - span_axis - load_axis;
  const double w = hi[width_axis] - lo[width_axis], h = hi[load_axis] - lo[load_axis];
  const double I = w * h * h * h / 12.0, A = w * h;
  // the supports push against the load: their reaction is the load carried by the beam
  r.load = std::abs(total_force(p, pin)[load_axis] + total_force(p, roller)[load_axis]);
  r.span =
      std::abs(reference_centroid(p, roller)[span_axis] - reference_centroid(p, pin)[span_axis]);
  double xmin = p.reference_position[loaded.members[0]][span_axis], xmax = xmin;
  for (int i : loaded.members)
  {
    xmin = std::min(xmin, p.reference_position[i][span_axis]);
    xmax = std::max(xmax, p.reference_position[i][span_axis]);
  }
  r.load_length = xmax - xmin;
  const double top = std::abs(mean_displacement(p, loaded)[load_axis]);
  r.bottom_deflection = std::abs(mean_displacement(p, bottom)[load_axis]);
  r.deflection = 0.5 * (top + r.bottom_deflection);
  if (!(r.span > 0))
    return r;
  const double L = r.span, b = r.load_length;
  r.compliance_factor_point = L * L * L / (24 * I) + L * fs * (1 + nu) / A; // eq. 67
  r.compliance_factor =
      (8 * L * L * L - 4 * b * b * L + b * b * b) / (192 * I) + fs * (L - b) * (1 + nu) / A;
  if (!(r.deflection > 0))
    return r;
  r.flexural_modulus_point = r.load / (2 * r.deflection) * r.compliance_factor_point;
  r.flexural_modulus = r.load / (2 * r.deflection) * r.compliance_factor;               // eq. 69
  r.flexural_modulus_bottom = r.load / (2 * r.bottom_deflection) * r.compliance_factor; // bottom
  return r;
}

ModulusFit fit_flexural_modulus(const std::vector<double>& deflection,
                                const std::vector<double>& load, const FlexuralResponse& geometry)
{
  ModulusFit fit;
  double suu = 0, suf = 0;
  for (std::size_t k = 0; k < deflection.size() && k < load.size(); ++k)
  {
    const double u = std::abs(deflection[k]), f = std::abs(load[k]);
    suu += u * u, suf += u * f;
    fit.points += u > 0;
  }
  if (fit.points < 2 || !(suu > 0))
    return fit;
  fit.youngs_modulus = suf / suu / 2 * geometry.compliance_factor; // eq. 69 with F/delta = slope
  return fit;
}

double largest_rotation(const ParticleStore& p, const BondStore& b)
{
  double largest = 0;
  for (const Quat& q : p.orientation) // angle = 2 atan2(|vector part|, |w|)
    largest = std::max(largest, 2 * std::atan2(q.vec().norm(), std::abs(q.w())));
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const auto i = std::size_t(b.a[k]), j = std::size_t(b.b[k]);
    const Vec3 now = p.position[j] - p.position[i];
    const Vec3 then = p.reference_position[j] - p.reference_position[i];
    largest = std::max(largest, std::atan2(now.cross(then).norm(), now.dot(then)));
  }
  return largest;
}
} // namespace dembridge::dem
