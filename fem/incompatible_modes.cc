// dembridge::fem — the Q1 hexahedron with incompatible modes (incompatible_modes.h).
#include "fem/incompatible_modes.h"

#include <deal.II/fe/fe.h>

#include <algorithm>
#include <array>

namespace dembridge::fem
{
using namespace dealii;

void condense_incompatible_modes(const FEValues<3>& fe_values,
                                 const SymmetricTensor<4, 3>& stiffness,
                                 const std::function<double(const Point<3>&)>& weight,
                                 const Tensor<1, 3>& body_force,
                                 const DerivativeForm<1, 3, 3>& centre_inverse_jacobian,
                                 const double centre_det_jacobian, FullMatrix<double>& cell_matrix,
                                 Vector<double>& cell_rhs)
{
  const auto& fe = fe_values.get_fe();
  const auto& quadrature = fe_values.get_quadrature();
  const unsigned int n = fe.n_dofs_per_cell();
  constexpr unsigned int modes = 9; // P_a for a = x, y, z, each in three components
  FullMatrix<double> K_ua(n, modes), K_aa(modes, modes);
  Vector<double> f_a(modes);
  std::vector<SymmetricTensor<2, 3>> eps_u(n), eps_a(modes);
  std::array<double, 3> bubble{};
  double lightest = 1; // the smallest stiffness weight over the Gauss points
  for (const unsigned int q : fe_values.quadrature_point_indices())
  {
    const Point<3>& unit = quadrature.point(q); // in [0, 1]^3
    const double JxW = fe_values.JxW(q);
    // Taylor's correction: the centre's Jacobian, scaled by det J0 / det J(q)
    const double scale = centre_det_jacobian / (JxW / quadrature.weight(q));
    for (unsigned int a = 0; a < 3; ++a)
    {
      const double xi = 2 * unit[a] - 1;
      bubble[a] = 1 - xi * xi;
      Tensor<1, 3> gradient; // d P_a / d x = dP_a/dx^_a (dx^_a / dx): dP/dx^ = -4 xi
      for (unsigned int b = 0; b < 3; ++b)
        gradient[b] = scale * (-4 * xi) * centre_inverse_jacobian[a][b];
      for (unsigned int c = 0; c < 3; ++c)
      {
        Tensor<1, 3> e;
        e[c] = 1;
        eps_a[3 * a + c] = symmetrize(outer_product(e, gradient));
      }
    }
    for (unsigned int i = 0; i < n; ++i)
    {
      Tensor<1, 3> e;
      e[fe.system_to_component_index(i).first] = 1;
      eps_u[i] = symmetrize(outer_product(e, fe_values.shape_grad(i, q)));
    }
    const double w = weight ? weight(fe_values.quadrature_point(q)) : 1.0;
    lightest = std::min(lightest, w);
    for (unsigned int k = 0; k < modes; ++k)
    {
      const SymmetricTensor<2, 3> C_eps = stiffness * eps_a[k];
      for (unsigned int i = 0; i < n; ++i)
        K_ua(i, k) += w * (C_eps * eps_u[i]) * JxW;
      for (unsigned int l = 0; l < modes; ++l)
        K_aa(k, l) += w * (C_eps * eps_a[l]) * JxW;
      f_a(k) += bubble[k / 3] * body_force[k % 3] * JxW;
    }
  }
  // Each Gauss point contributes a rank-6 part to K_aa; with every weight positive the nine
  // modes are stiff. A cell where the weight vanishes somewhere keeps K_uu.
  if (!(lightest > 0))
    return;
  K_aa.gauss_jordan();
  FullMatrix<double> T(n, modes); // K_ua K_aa^-1
  K_ua.mmult(T, K_aa);
  FullMatrix<double> correction(n, n);
  T.mTmult(correction, K_ua);
  cell_matrix.add(-1.0, correction);
  Vector<double> rhs_correction(n);
  T.vmult(rhs_correction, f_a);
  cell_rhs -= rhs_correction;
}
} // namespace dembridge::fem
