// Elastic properties of a 6x6 stiffness, the simple cubic closed form and the finite specimen's
// measured tensor (equations and sources in elasticity_tensor.h; the periodic cell is in
// periodic_elasticity.cc).
#include "dem/measurements/elasticity_tensor.h"
#include "dem/measurements/particle_stress.h"
#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <sstream>

namespace dembridge::dem
{
Eigen::Matrix3d strain_tensor(const Vector6& e)
{
  Eigen::Matrix3d E;
  E << e[0], 0.5 * e[5], 0.5 * e[4], //
      0.5 * e[5], e[1], 0.5 * e[3],  //
      0.5 * e[4], 0.5 * e[3], e[2];
  return E;
}

Vector6 voigt_stress(const Eigen::Matrix3d& s)
{
  const Eigen::Matrix3d t = 0.5 * (s + s.transpose());
  Vector6 v;
  v << t(0, 0), t(1, 1), t(2, 2), t(1, 2), t(0, 2), t(0, 1);
  return v;
}

Matrix6 rotate_stiffness(const Matrix6& C, const Eigen::Matrix3d& Q)
{
  const int voigt[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
  Matrix6 out = Matrix6::Zero();
  // C'_IJ = sum_abcd Q_ia Q_jb Q_kc Q_ld C_(ab)(cd) for (ij) -> I, (kl) -> J
  const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  for (int I = 0; I < 6; ++I)
    for (int J = 0; J < 6; ++J)
    {
      const int i = pairs[I][0], j = pairs[I][1], k = pairs[J][0], l = pairs[J][1];
      double sum = 0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          for (int c = 0; c < 3; ++c)
            for (int d = 0; d < 3; ++d)
              sum += Q(i, a) * Q(j, b) * Q(k, c) * Q(l, d) * C(voigt[a][b], voigt[c][d]);
      out(I, J) = sum;
    }
  return out;
}

ElasticProperties elastic_properties(const Matrix6& C, const std::string& where)
{
  const double scale = C.cwiseAbs().maxCoeff();
  if (!(scale > 0) || !C.allFinite())
    throw InputError(where + ": the stiffness tensor is zero or not finite");
  if ((C - C.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    throw InputError(where + ": the stiffness tensor is not symmetric");
  const Eigen::SelfAdjointEigenSolver<Matrix6> eig(C);
  if (!(eig.eigenvalues().minCoeff() > 1e-12 * scale))
  {
    std::ostringstream s;
    s << where << ": the stiffness tensor is not positive definite (smallest eigenvalue "
      << eig.eigenvalues().minCoeff() << " Pa)";
    throw InputError(s.str());
  }
  ElasticProperties p;
  p.stiffness = C;
  p.compliance = C.inverse();
  const Matrix6& S = p.compliance;
  for (int i = 0; i < 3; ++i)
  {
    p.youngs_modulus[i] = 1.0 / S(i, i);
    p.shear_modulus[i] = 1.0 / S(3 + i, 3 + i);
    for (int j = 0; j < 3; ++j)
      p.poisson_ratio(i, j) = i == j ? 0.0 : -S(j, i) / S(i, i);
  }
  // Voigt and Reuss bounds (Hill 1952), Ranganathan & Ostoja-Starzewski (2008) eq. 6
  const double c_diag = C(0, 0) + C(1, 1) + C(2, 2), c_off = C(0, 1) + C(1, 2) + C(0, 2),
               c_shear = C(3, 3) + C(4, 4) + C(5, 5);
  const double s_diag = S(0, 0) + S(1, 1) + S(2, 2), s_off = S(0, 1) + S(1, 2) + S(0, 2),
               s_shear = S(3, 3) + S(4, 4) + S(5, 5);
  p.bulk_modulus_voigt = (c_diag + 2 * c_off) / 9;
  p.shear_modulus_voigt = (c_diag - c_off + 3 * c_shear) / 15;
  p.bulk_modulus_reuss = 1.0 / (s_diag + 2 * s_off);
  p.shear_modulus_reuss = 15.0 / (4 * s_diag - 4 * s_off + 3 * s_shear);
  p.universal_anisotropy = 5 * p.shear_modulus_voigt / p.shear_modulus_reuss +
                           p.bulk_modulus_voigt / p.bulk_modulus_reuss - 6;
  p.zener_ratio = 2 * (c_shear / 3) / (c_diag / 3 - c_off / 3);
  return p;
}

Matrix6 simple_cubic_stiffness(double kn, double ks, double d)
{
  Matrix6 C = Matrix6::Zero();
  for (int i = 0; i < 3; ++i)
  {
    C(i, i) = kn / d;               // C11 = k_n / d
    C(3 + i, 3 + i) = 0.5 * ks / d; // C44 = k_s / (2 d)
  }
  return C;
}

Matrix6 simple_cubic_stiffness(const BondMaterial& material, double r)
{
  const BondStiffness k = bond_stiffness(material, 2 * r, r, r);
  return simple_cubic_stiffness(k.kn, k.ks, 2 * r);
}

namespace
{
/// The core's strain: the symmetric part of G in the least-squares fit u = a + G x over the
/// particles whose centres lie in [lo, hi] (engineering shears, Voigt order).
Vector6 core_strain(const ParticleStore& p, const Vec3& lo, const Vec3& hi)
{
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Matrix<double, 4, 3> rhs = Eigen::Matrix<double, 4, 3>::Zero();
  const Vec3 centre = 0.5 * (lo + hi); // conditioning: coordinates about the core's centre
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec3& x = p.reference_position[i];
    if (!((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()))
      continue;
    Eigen::Vector4d row;
    row << 1.0, x - centre;
    normal += row * row.transpose();
    rhs += row * (p.position[i] - x).transpose();
  }
  const Eigen::LDLT<Eigen::Matrix4d> fit(normal);
  if (fit.info() != Eigen::Success || !(fit.vectorD().cwiseAbs().minCoeff() > 0))
    throw InputError("elasticity measurement: the core's particle centres lie in one plane; "
                     "its strain cannot be measured (a larger specimen or a smaller core margin)");
  const Eigen::Matrix3d G = fit.solve(rhs).bottomRows<3>().transpose(); // du_i/dx_j
  Vector6 e;
  e << G(0, 0), G(1, 1), G(2, 2), G(1, 2) + G(2, 1), G(0, 2) + G(2, 0), G(0, 1) + G(1, 0);
  return e;
}
} // namespace

MeasuredElasticity measured_stiffness_tensor(const Model& model,
                                             const ElasticityMeasurementSettings& s)
{
  using clock = std::chrono::steady_clock;
  const std::string where = "elasticity measurement";
  // A bare copy: the case's supports, loads and groups play no part.
  Model m;
  m.particles = model.particles;
  m.bonds = model.bonds;
  ParticleStore& p = m.particles;
  const std::size_t n = p.size();
  if (n == 0)
    throw InputError(where + ": the packing has no particle");
  MeasuredElasticity out;
  out.n_particles = long(n);
  for (std::size_t k = 0; k < m.bonds.size(); ++k)
    out.n_bonds += m.bonds.state[k] == BondState::intact;
  if (out.n_bonds == 0)
    throw InputError(where + ": the packing has no intact bond");

  const auto [lo, hi] = reference_extent(p);
  out.extent_lo = lo, out.extent_hi = hi;
  double mean_diameter = 0;
  for (double r : p.radius)
    mean_diameter += 2 * r / double(n);
  const double margin = s.core_margin * mean_diameter;
  out.core_lo = lo + Vec3::Constant(margin);
  out.core_hi = hi - Vec3::Constant(margin);
  for (int d = 0; d < 3; ++d) // whole lattice periods: the box holds exactly its share
    if (s.core_period[d] > 0)
      out.core_hi[d] = out.core_lo[d] +
                       s.core_period[d] *
                           std::floor((out.core_hi[d] - out.core_lo[d]) / s.core_period[d] + 1e-9);
  if (!((out.core_hi - out.core_lo).array() > 0).all())
  {
    std::ostringstream msg;
    msg << where << ": the specimen (" << (hi - lo).transpose()
        << " m) has no core: it must be wider than twice the core margin of " << s.core_margin
        << " mean diameters (" << margin << " m) in every direction";
    throw InputError(msg.str());
  }
  out.core_volume = (out.core_hi - out.core_lo).prod();

  std::vector<int> held;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3& x = p.reference_position[i];
    const double t = s.boundary_thickness * p.radius[i] * (1.0 + 1e-9);
    if (((x - lo).array() <= t).any() || ((hi - x).array() <= t).any())
      held.push_back(int(i));
    if ((x.array() >= out.core_lo.array()).all() && (x.array() <= out.core_hi.array()).all())
      ++out.n_core;
  }
  out.n_held = long(held.size());
  if (held.empty())
    throw InputError(where + ": no particle lies within the boundary thickness of a face");
  if (out.n_core < 4)
    throw InputError(where + ": the core box holds " + std::to_string(out.n_core) +
                     " particle centres, too few to measure its strain (a larger specimen or a "
                     "smaller core margin)");

  const auto t0 = clock::now();
  StaticSettings settings = s.solver;
  Matrix6 stresses, strains; // column J: the core's Voigt stress and strain under strain J
  for (int J = 0; J < 6; ++J)
  {
    Vector6 e = Vector6::Zero();
    e[J] = s.strain;
    const Eigen::Matrix3d E = strain_tensor(e);
    // reset to the reference state (the solver writes its equilibrium into the particles)
    for (std::size_t i = 0; i < n; ++i)
    {
      p.position[i] = p.reference_position[i];
      p.orientation[i] = Quat::Identity();
    }
    settings.prescribed.clear();
    for (int i : held)
    {
      StaticSettings::PrescribedDisplacement d;
      d.index = i;
      d.dofs = 63;                                     // translations and rotations
      d.value.head<3>() = E * p.reference_position[i]; // u = E x (affine)
      settings.prescribed.push_back(d);                // rotation: 0 (E symmetric)
    }
    const StaticResult r = solve_static(m, settings);
    out.max_residual = std::max(out.max_residual, r.residual);
    const ParticleStresses ps = particle_stresses(p, m.bonds, StressTheory::small_strain);
    const Eigen::Matrix3d sigma = rve_average(p, ps, out.core_lo, out.core_hi, out.core_volume);
    const double norm = sigma.norm();
    if (norm > 0)
      out.stress_asymmetry =
          std::max(out.stress_asymmetry, (sigma - sigma.transpose()).norm() / norm);
    stresses.col(J) = voigt_stress(sigma);
    strains.col(J) = core_strain(p, out.core_lo, out.core_hi);
  }
  out.solve_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  out.core_strain_deviation =
      (strains - s.strain * Matrix6::Identity()).cwiseAbs().maxCoeff() / s.strain;
  out.raw_stiffness = stresses * strains.inverse();
  const Matrix6& A = out.raw_stiffness;
  out.symmetry_error = (A - A.transpose()).cwiseAbs().maxCoeff() / A.cwiseAbs().maxCoeff();
  out.properties = elastic_properties(0.5 * (A + A.transpose()), where);
  return out;
}
} // namespace dembridge::dem
