#include "dem/bonds/bond_matrix.h"
#include <numbers>

namespace dembridge::dem
{
namespace
{
Eigen::Matrix3d skew(const Vec3& v)
{
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

/// B maps [u_a, th_a, u_b, th_b] to [delta (3), rotation a - b (3)] at the contact point:
///   delta = u_a - u_b + th_a x r_ac - th_b x r_bc,  r_ac = s L x, r_bc = -(1-s) L x
Eigen::Matrix<double, 6, 12> contact_point_map(double s, double L)
{
  const Vec3 rac(s * L, 0, 0), rbc((s - 1.0) * L, 0, 0);
  Eigen::Matrix<double, 6, 12> B = Eigen::Matrix<double, 6, 12>::Zero();
  B.block<3, 3>(0, 0) = Eigen::Matrix3d::Identity();
  B.block<3, 3>(0, 3) = -skew(rac); // th x r = -r x th
  B.block<3, 3>(0, 6) = -Eigen::Matrix3d::Identity();
  B.block<3, 3>(0, 9) = skew(rbc);
  B.block<3, 3>(3, 3) = Eigen::Matrix3d::Identity();
  B.block<3, 3>(3, 9) = -Eigen::Matrix3d::Identity();
  return B;
}
} // namespace

Matrix12 unified_bond_matrix(const BondStiffness& k, double L)
{
  const Eigen::Matrix<double, 6, 12> B = contact_point_map(k.contact_fraction, L);
  Eigen::Matrix<double, 6, 1> D;
  D << k.kn, k.ks, k.ks, k.ktor, k.kben, k.kben;
  return B.transpose() * D.asDiagonal() * B;
}

Matrix12 smooth_joint_matrix(const BondStiffness& k, double L, const Vec3& n)
{
  const Eigen::Matrix<double, 6, 12> B = contact_point_map(k.contact_fraction, L);
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.topLeftCorner<3, 3>() =
      k.kn * n * n.transpose() + k.ks * (Eigen::Matrix3d::Identity() - n * n.transpose());
  return B.transpose() * D * B;
}

Matrix12 timoshenko_beam_matrix(double E, double nu, double r, double L)
{
  const double pi = std::numbers::pi;
  const double A = pi * r * r, I = 0.25 * pi * r * r * r * r;
  const double phi = 20.0 * r * r * (1.0 + nu) / (3.0 * L * L); // eq. 31
  const double c = E * I / (L * L * L * (1.0 + phi));
  Eigen::Matrix3d K1 = Eigen::Matrix3d::Zero(), K2 = Eigen::Matrix3d::Zero(),
                  K3 = Eigen::Matrix3d::Zero(), K4 = Eigen::Matrix3d::Zero();
  K1.diagonal() << E * A / L, 12.0 * c, 12.0 * c; // eq. 27
  K2(1, 2) = -6.0 * c * L;                        // eq. 28
  K2(2, 1) = 6.0 * c * L;
  const double tor = E * I / (L * (1.0 + nu));
  K3.diagonal() << tor, E * I * (4.0 + phi) / (L * (1.0 + phi)),
      E * I * (4.0 + phi) / (L * (1.0 + phi)); // eq. 29
  K4.diagonal() << -tor, E * I * (2.0 - phi) / (L * (1.0 + phi)),
      E * I * (2.0 - phi) / (L * (1.0 + phi)); // eq. 30
  Matrix12 K;
  // eq. 26: [K1 -K2 -K1 -K2; K2 K3 -K2 K4; -K1 K2 K1 K2; K2 K4 -K2 K3] with the thesis'
  // block convention that K2 acting on rotations enters transposed (K is symmetric).
  K.block<3, 3>(0, 0) = K1;
  K.block<3, 3>(0, 3) = K2.transpose();
  K.block<3, 3>(0, 6) = -K1;
  K.block<3, 3>(0, 9) = K2.transpose();
  K.block<3, 3>(3, 0) = K2;
  K.block<3, 3>(3, 3) = K3;
  K.block<3, 3>(3, 6) = -K2;
  K.block<3, 3>(3, 9) = K4;
  K.block<3, 3>(6, 0) = -K1;
  K.block<3, 3>(6, 3) = -K2.transpose();
  K.block<3, 3>(6, 6) = K1;
  K.block<3, 3>(6, 9) = -K2.transpose();
  K.block<3, 3>(9, 0) = K2;
  K.block<3, 3>(9, 3) = K4;
  K.block<3, 3>(9, 6) = -K2;
  K.block<3, 3>(9, 9) = K3;
  return K;
}

Eigen::Matrix3d bond_frame(const Vec3& e)
{
  Vec3 y = e.cross(Vec3::UnitZ());
  if (y.norm() < 1e-12)
    y = Vec3::UnitY(); // eq. 7
  else
    y.normalize();
  Eigen::Matrix3d R;
  R.col(0) = e;
  R.col(1) = y;
  R.col(2) = e.cross(y).normalized(); // eq. 8
  return R;
}
} // namespace dembridge::dem
