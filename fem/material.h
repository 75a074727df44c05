// dembridge::fem — linear elastic stiffness tensors.
//
// Isotropic: C_ijkl = lambda d_ij d_kl + mu (d_ik d_jl + d_il d_jk),
//   lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).
// Anisotropic: a symmetric positive definite 6x6 Voigt matrix C_IJ with the order
//   I = xx, yy, zz, yz, xz, xy and engineering shear strains (gamma_yz = 2 eps_yz), so that
//   sigma_I = C_IJ eps_J and C_ijkl = C_IJ for (ij) -> I, (kl) -> J.
#pragma once

#include "parameters.h"

#include <deal.II/base/symmetric_tensor.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dembridge::fem
{
inline dealii::SymmetricTensor<4, 3> isotropic_stiffness(const double E, const double nu)
{
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = E / (2 * (1 + nu));
  dealii::SymmetricTensor<4, 3> C;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      for (unsigned int k = 0; k < 3; ++k)
        for (unsigned int l = 0; l < 3; ++l)
          C[i][j][k][l] = (i == j && k == l ? lambda : 0.0) + ((i == k && j == l) ? mu : 0.0) +
                          ((i == l && j == k) ? mu : 0.0);
  return C;
}

/// Voigt index of the symmetric pair (i, j): xx=0, yy=1, zz=2, yz=3, xz=4, xy=5.
inline unsigned int voigt_index(const unsigned int i, const unsigned int j)
{
  if (i == j)
    return i;
  return 6 - i - j; // (1,2)->3, (0,2)->4, (0,1)->5
}

/// Stiffness tensor from a row-major 6x6 Voigt matrix; throws if it is not symmetric positive
/// definite (Cholesky).
inline dealii::SymmetricTensor<4, 3> voigt_stiffness(const std::array<double, 36>& c)
{
  const std::string where = "FEM/Material/voigt stiffness";
  double scale = 0;
  for (const double v : c)
    scale = std::max(scale, std::abs(v));
  for (unsigned int I = 0; I < 6; ++I)
    for (unsigned int J = 0; J < I; ++J)
      if (std::abs(c[6 * I + J] - c[6 * J + I]) > 1e-12 * scale)
        throw std::runtime_error(where + ": the 6x6 matrix is not symmetric");
  std::array<double, 36> L{};
  for (unsigned int j = 0; j < 6; ++j)
  {
    double d = c[6 * j + j];
    for (unsigned int k = 0; k < j; ++k)
      d -= L[6 * j + k] * L[6 * j + k];
    if (!(d > 1e-12 * scale))
      throw std::runtime_error(where + ": the 6x6 matrix is not positive definite");
    L[6 * j + j] = std::sqrt(d);
    for (unsigned int i = j + 1; i < 6; ++i)
    {
      double s = c[6 * i + j];
      for (unsigned int k = 0; k < j; ++k)
        s -= L[6 * i + k] * L[6 * j + k];
      L[6 * i + j] = s / L[6 * j + j];
    }
  }
  dealii::SymmetricTensor<4, 3> C;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      for (unsigned int k = 0; k < 3; ++k)
        for (unsigned int l = k; l < 3; ++l)
          C[i][j][k][l] = c[6 * voigt_index(i, j) + voigt_index(k, l)];
  return C;
}

inline dealii::SymmetricTensor<4, 3> stiffness_tensor(const Parameters& p)
{
  return p.material == MaterialModel::isotropic
             ? isotropic_stiffness(p.youngs_modulus, p.poisson_ratio)
             : voigt_stiffness(p.voigt_stiffness);
}

} // namespace dembridge::fem
