// The ideal lattice's stiffness tensor from one periodic cell (elasticity_tensor.h, item 2):
//   u_p(R) = E (x_p + R) + w_p,  theta_p(R) = theta_p,
//   W_cell = 1/2 sum_{bonds of the cell} u_b^T K_g u_b,   K_g = T K_l T^T (thesis eq. 32),
//   C = (1 / V_cell) (K_ee - K_ez K_zz^-1 K_ze)     (static condensation of the internal DOFs z).
// K_l is the 12x12 unified bond matrix (bond_matrix.h), the same the static solver assembles,
// so the periodic and the finite-specimen tensors come from one bond law.
#include "dem/bonds/bond_matrix.h"
#include "dem/measurements/elasticity_tensor.h"
#include <Eigen/Eigenvalues>
#include <cmath>

namespace dembridge::dem
{
LatticeCell lattice_cell(ParticleSource::Kind kind, double r)
{
  if (!(r > 0) || !std::isfinite(r))
    throw InputError("Particles/radius: must be positive for a lattice cell");
  using K = ParticleSource::Kind;
  LatticeCell c;
  const double s3 = std::sqrt(3.0), dz = 2.0 * std::sqrt(2.0 / 3.0) * r; // layer spacing
  switch (kind)
  {
  case K::cubic:
    c.vectors = 2 * r * Eigen::Matrix3d::Identity();
    c.basis = {Vec3::Zero()};
    break;
  case K::hcp: // rows along x (2r), rows offset by (r, sqrt3 r), B layer over the "up" hollows
    c.vectors.col(0) = Vec3(2 * r, 0, 0);
    c.vectors.col(1) = Vec3(r, s3 * r, 0);
    c.vectors.col(2) = Vec3(0, 0, 2 * dz);
    c.basis = {Vec3::Zero(), Vec3(r, r / s3, dz)};
    break;
  case K::fcc: // ABC: each layer shifted by (r, r/sqrt3) over the one below
    c.vectors.col(0) = Vec3(2 * r, 0, 0);
    c.vectors.col(1) = Vec3(r, s3 * r, 0);
    c.vectors.col(2) = Vec3(r, r / s3, dz);
    c.basis = {Vec3::Zero()};
    break;
  default:
    throw InputError("Particles/source: a periodic cell exists only for the cubic, hcp and fcc "
                     "lattices");
  }
  c.radius.assign(c.basis.size(), r);
  return c;
}

Vec3 lattice_axis_periods(ParticleSource::Kind kind, double r)
{
  using K = ParticleSource::Kind;
  switch (kind)
  {
  case K::cubic:
    return Vec3::Constant(2 * r);
  case K::hcp:
  case K::fcc:
    return Vec3(2 * r, std::sqrt(3.0) * r, 2.0 * std::sqrt(2.0 / 3.0) * r);
  default:
    return Vec3::Zero();
  }
}

namespace
{
/// d(E d)/d(e_J): the affine displacement of the bond vector d per Voigt strain component.
Eigen::Matrix<double, 3, 6> affine_map(const Vec3& d)
{
  Eigen::Matrix<double, 3, 6> G = Eigen::Matrix<double, 3, 6>::Zero();
  G(0, 0) = d.x(), G(1, 1) = d.y(), G(2, 2) = d.z();
  G(1, 3) = 0.5 * d.z(), G(2, 3) = 0.5 * d.y(); // gamma_yz
  G(0, 4) = 0.5 * d.z(), G(2, 4) = 0.5 * d.x(); // gamma_xz
  G(0, 5) = 0.5 * d.y(), G(1, 5) = 0.5 * d.x(); // gamma_xy
  return G;
}
} // namespace

PeriodicElasticity periodic_stiffness_tensor(const LatticeCell& cell, const BondMaterial& material,
                                             double eta)
{
  const std::string where = "periodic cell";
  const int nb = int(cell.basis.size());
  if (nb == 0 || cell.radius.size() != cell.basis.size())
    throw InputError(where + ": the cell has no basis or radii of another length");
  const double volume = std::abs(cell.vectors.determinant());
  if (!(volume > 0))
    throw InputError(where + ": the lattice vectors span no volume");
  material.validate("Bonds");

  // Images to search: enough cells along each lattice vector to reach the longest bond.
  double rmax = 0, reach = 0;
  for (int p = 0; p < nb; ++p)
  {
    rmax = std::max(rmax, cell.radius[p]);
    for (int q = 0; q < nb; ++q)
      reach = std::max(reach, (cell.basis[q] - cell.basis[p]).norm());
  }
  const double cutoff = 2 * eta * rmax * (1 + 1e-9);
  const Eigen::Matrix3d inv = cell.vectors.inverse();
  int range[3];
  for (int i = 0; i < 3; ++i)
    range[i] = int(std::ceil((cutoff + reach) * inv.row(i).norm())) + 1; // 1/|row| = spacing

  const int N = 6 + 6 * nb; // [e (Voigt); w_0, theta_0, w_1, theta_1, ...]
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
  long ordered = 0;
  for (int p = 0; p < nb; ++p)
    for (int q = 0; q < nb; ++q)
      for (int i = -range[0]; i <= range[0]; ++i)
        for (int j = -range[1]; j <= range[1]; ++j)
          for (int k = -range[2]; k <= range[2]; ++k)
          {
            if (p == q && i == 0 && j == 0 && k == 0)
              continue;
            const Vec3 d = cell.basis[q] + cell.vectors * Vec3(i, j, k) - cell.basis[p];
            const double L = d.norm();
            if (L > eta * (cell.radius[p] + cell.radius[q]) * (1 + 1e-9)) // bonding.h
              continue;
            ++ordered;
            const Matrix12 Kl =
                unified_bond_matrix(bond_stiffness(material, L, cell.radius[p], cell.radius[q]), L);
            const Eigen::Matrix3d R = bond_frame(d / L);
            Matrix12 T = Matrix12::Zero();
            for (int b = 0; b < 4; ++b)
              T.block<3, 3>(3 * b, 3 * b) = R;
            const Matrix12 Kg = T * Kl * T.transpose();
            // u_b = P z: [w_p, theta_p, w_q + E d, theta_q]
            Eigen::MatrixXd P = Eigen::MatrixXd::Zero(12, N);
            P.block<6, 6>(0, 6 + 6 * p) = Matrix6::Identity();
            P.block<6, 6>(6, 6 + 6 * q) += Matrix6::Identity();
            P.block<3, 6>(6, 0) = affine_map(d);
            K.noalias() += 0.5 * P.transpose() * Kg * P; // each bond is seen from both ends
          }
  if (ordered == 0)
    throw InputError(where + ": no two particles are within bonding range (contact radius "
                             "multiplier too small?)");

  // Internal DOFs: all but the strain and the translation of particle 0 (rigid translation).
  std::vector<int> z;
  for (int d = 9; d < N; ++d)
    z.push_back(d);
  const int nz = int(z.size());
  Eigen::MatrixXd Kzz(nz, nz), Kze(nz, 6);
  for (int a = 0; a < nz; ++a)
  {
    for (int b = 0; b < nz; ++b)
      Kzz(a, b) = K(z[a], z[b]);
    for (int b = 0; b < 6; ++b)
      Kze(a, b) = K(z[a], b);
  }
  // Jacobi-scaled, so that N/m and N·m/rad DOFs compare: a mechanism is a zero eigenvalue.
  const Eigen::VectorXd scale = Kzz.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd Kzz_scaled = scale.asDiagonal() * Kzz * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kzz_scaled);
  if (!(eig.eigenvalues().minCoeff() > 1e-10 * eig.eigenvalues().maxCoeff()))
    throw InputError(where + ": the cell has a mechanism (a sublattice shift or rotation that "
                             "costs no energy)");
  const Eigen::MatrixXd relaxed =
      scale.asDiagonal() * Kzz_scaled.ldlt().solve(scale.asDiagonal() * Kze);
  Matrix6 C = (K.topLeftCorner<6, 6>() - Kze.transpose() * relaxed) / volume;
  C = 0.5 * (C + C.transpose()).eval();

  PeriodicElasticity out;
  out.properties = elastic_properties(C, where);
  out.cell_volume = volume;
  out.n_basis = nb;
  out.n_bonds_per_cell = int(ordered / 2);
  out.mean_coordination = double(ordered) / nb;
  return out;
}
} // namespace dembridge::dem
