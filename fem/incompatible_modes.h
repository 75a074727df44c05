#pragma once
// The trilinear hexahedron with incompatible modes (Wilson, Taylor, Doherty & Ghaboussi 1973;
// Taylor, Beresford & Wilson 1976, "QM6" in 3-D): the displacement of a cell is enriched by
// three bubble modes per component,
//   u_c(x) = sum_I N_I(xi) u_Ic + sum_a P_a(xi) alpha_ac,   P_a = 1 - xi_a^2,  xi in [-1, 1]^3,
// whose amplitudes alpha live inside the cell and are condensed out statically:
//   K_e = K_uu - K_ua K_aa^-1 K_au,    f_e = f_u - K_ua K_aa^-1 f_a.
// The modes give the cell the linear strain variation of bending that the trilinear field can
// only imitate by a parasitic shear strain, so a Q1 beam with a few cells through its depth no
// longer locks: pure bending of rectangular cells is exact whatever their aspect ratio. The
// gradients are taken with the Jacobian at the cell centre, scaled by det J0 / det J (Taylor's
// correction), so that int B_a dV = 0: a uniform stress does no work on the modes and the cell
// passes the patch test on any parallelepiped (the coupled mode's cells are boxes).
// Integrated with the 2x2x2 Gauss rule of the cell matrix (exact on parallelepipeds).
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <functional>

namespace dembridge::fem
{
/// Condenses the nine incompatible modes of the cell that @p fe_values (FE_Q1^3, Gauss rule,
/// with values, gradients, quadrature points, JxW and inverse Jacobians) was reinit'ed on into
/// @p cell_matrix (the cell's compatible 24 x 24 K_uu on entry) and @p cell_rhs (f_u on entry;
/// body force @p body_force). @p weight scales the stiffness at a point (1 - alpha in a
/// coupled band); a cell whose modes carry no stiffness keeps K_uu. @p centre_inverse_jacobian
/// and @p centre_det_jacobian: J0^-1 and det J0 at the cell centre (unit cell [0, 1]^3).
void condense_incompatible_modes(const dealii::FEValues<3>& fe_values,
                                 const dealii::SymmetricTensor<4, 3>& stiffness,
                                 const std::function<double(const dealii::Point<3>&)>& weight,
                                 const dealii::Tensor<1, 3>& body_force,
                                 const dealii::DerivativeForm<1, 3, 3>& centre_inverse_jacobian,
                                 double centre_det_jacobian,
                                 dealii::FullMatrix<double>& cell_matrix,
                                 dealii::Vector<double>& cell_rhs);
} // namespace dembridge::fem
