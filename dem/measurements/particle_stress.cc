#include "dem/measurements/particle_stress.h"
#include "dem/bonds/bond_kernel.h"
#include "dem/bonds/bond_matrix.h"
#include <algorithm>
#include <cmath>
#include <numbers>

namespace dembridge::dem
{
namespace
{
/// The unified bond law at the current state; with dashpots it reads the particles' velocities.
template <bool dashpots>
BondForces bond_law_now(const ParticleStore& p, const BondStore& b, std::size_t k)
{
  const int ia = b.a[k], ib = b.b[k];
  const BondConstants c{b.rest_length[k],
                        b.rest_axis[k],
                        b.kn[k],
                        b.ks[k],
                        b.ktor[k],
                        b.kben[k],
                        b.contact_fraction[k],
                        b.damping_force[k],
                        b.damping_moment[k]};
  BondForces f; // without dashpots bond_law reads no velocity
  bond_law<dashpots>(p.position[ia].data(), p.position[ib].data(),
                     p.orientation[ia].coeffs().data(), p.orientation[ib].coeffs().data(),
                     p.velocity[ia].data(), p.velocity[ib].data(), p.angular_velocity[ia].data(),
                     p.angular_velocity[ib].data(), c, f, b.joint_normal(k));
  return f;
}

/// The elastic bond law at the current configuration (no dashpots: velocities are not read).
BondForces elastic_bond_forces(const ParticleStore& p, const BondStore& b, std::size_t k)
{
  return bond_law_now<false>(p, b, k);
}

/// The contact force and couple on b that bond k carries: the law's, times 1 - D (bond_damage.h).
BondContactForce carried(const BondStore& b, std::size_t k, const BondForces& f)
{
  const double share = b.load_factor(k);
  return {share * Vec3(f.Fc[0], f.Fc[1], f.Fc[2]), share * Vec3(f.Mc[0], f.Mc[1], f.Mc[2])};
}

/// Force on b of the linearised law: -(K u) restricted to b's translation, K = R K_local R^T.
Vec3 linear_bond_force(const ParticleStore& p, const BondStore& b, std::size_t k)
{
  const Eigen::Matrix3d R = bond_frame(b.rest_axis[k]);
  const Vec3* N = b.joint_normal(k);
  const Vec3 local_normal = N ? Vec3(R.transpose() * *N) : Vec3::Zero();
  const Matrix12 K = bond_matrix(b.stiffness(k), b.rest_length[k], N ? &local_normal : nullptr);
  Vector12 u; // local components of [u_a, theta_a, u_b, theta_b]
  int block = 0;
  for (int i : {b.a[k], b.b[k]})
  {
    const Eigen::AngleAxisd rot(p.orientation[i]);
    u.segment<3>(3 * block++) = R.transpose() * (p.position[i] - p.reference_position[i]);
    u.segment<3>(3 * block++) = R.transpose() * (rot.angle() * rot.axis());
  }
  return -(R * (K.middleRows<3>(6) * u));
}
} // namespace

BondContactForce bond_contact_force(const ParticleStore& p, const BondStore& b, std::size_t k)
{
  if (!is_bonded(b.state[k]))
    return {};
  return carried(b, k, bond_law_now<true>(p, b, k));
}

void record_bond_forces(const ParticleStore& p, BondStore& b)
{
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    if (!is_bonded(b.state[k]))
      continue;
    const BondContactForce f = carried(b, k, elastic_bond_forces(p, b, k));
    b.force[k] = f.force;
    b.moment[k] = f.moment;
  }
}

ParticleStresses particle_stresses(const ParticleStore& p, const BondStore& b, StressTheory theory)
{
  ParticleStresses s;
  const std::size_t n = p.size();
  s.sigma.assign(n, Tensor3::Zero());
  s.volume.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    s.volume[i] = 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius[i], 3);

  for (std::size_t k = 0; k < b.size(); ++k)
  {
    if (!is_bonded(b.state[k]))
      continue;
    const int ia = b.a[k], ib = b.b[k];
    const BondForces f = elastic_bond_forces(p, b, k);
    // a softening bond carries (1 - D) of its trial forces and stores (1 - D) of their energy
    const double carried = b.load_factor(k);
    s.strain_energy += carried * f.strain_energy;
    // Force on b is F at the contact point, on a it is -F: x_c - x_a = s L e, x_c - x_b =
    // (s - 1) L e, with L e the reference or the current chord.
    Vec3 F, chord;
    if (theory == StressTheory::small_strain)
      F = carried * linear_bond_force(p, b, k), chord = b.rest_length[k] * b.rest_axis[k];
    else
      F = carried * Vec3(f.Fc[0], f.Fc[1], f.Fc[2]), chord = p.position[ib] - p.position[ia];
    const double s_c = b.contact_fraction[k];
    s.sigma[ib] += ((s_c - 1.0) * chord) * F.transpose();
    s.sigma[ia] -= (s_c * chord) * F.transpose();
  }
  for (std::size_t i = 0; i < n; ++i)
    s.sigma[i] /= s.volume[i];
  return s;
}

Tensor3 rve_average(const ParticleStore& p, const ParticleStresses& s, const Vec3& lo,
                    const Vec3& hi, double volume)
{
  Tensor3 sum = Tensor3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& x = p.reference_position[i];
    if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all())
      sum += s.volume[i] * s.sigma[i];
  }
  return sum / volume;
}

StressLayers stress_layers(const ParticleStore& p, const ParticleStresses& s, const Vec3& lo,
                           const Vec3& hi, int axis, int n)
{
  StressLayers l;
  l.axis = axis;
  const double h = (hi[axis] - lo[axis]) / n;
  for (int j = 0; j <= n; ++j)
    l.edges.push_back(lo[axis] + j * h);
  l.sigma.assign(n, Tensor3::Zero());
  l.count.assign(n, 0);
  double section = 1;
  for (int d = 0; d < 3; ++d)
    if (d != axis)
      section *= hi[d] - lo[d];
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const int j =
        std::clamp(int(std::floor((p.reference_position[i][axis] - lo[axis]) / h)), 0, n - 1);
    l.sigma[j] += s.volume[i] * s.sigma[i];
    ++l.count[j];
  }
  for (auto& t : l.sigma)
    t /= section * h;
  return l;
}

StressHistogram stress_histogram(const ParticleStresses& s, int c, int bins)
{
  StressHistogram h;
  h.component = c;
  const std::size_t n = s.sigma.size();
  if (n == 0 || bins < 1)
    return h;
  for (const auto& t : s.sigma)
    h.mean += t(c, c);
  h.mean /= double(n);
  for (const auto& t : s.sigma)
    h.std_dev += (t(c, c) - h.mean) * (t(c, c) - h.mean);
  h.std_dev = std::sqrt(h.std_dev / double(n));
  if (h.mean == 0)
    return h;
  double lo = 0, hi = 0;
  for (const auto& t : s.sigma)
  {
    const double q = t(c, c) / h.mean;
    lo = std::min(lo, q), hi = std::max(hi, q);
  }
  h.max_ratio = hi;
  lo = std::floor(2 * lo) / 2, hi = std::ceil(2 * hi) / 2;
  if (hi <= lo)
    hi = lo + 1;
  const double w = (hi - lo) / bins;
  for (int j = 0; j <= bins; ++j)
    h.edges.push_back(lo + j * w);
  h.counts.assign(bins, 0);
  for (const auto& t : s.sigma)
    ++h.counts[std::clamp(int((t(c, c) / h.mean - lo) / w), 0, bins - 1)];
  return h;
}
} // namespace dembridge::dem
