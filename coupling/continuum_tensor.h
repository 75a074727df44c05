#pragma once
// The continuum's elasticity tensor in a coupled run: both sides must be the same material, so
// the FE carries the lattice's own (anisotropic) tensor, not an isotropic fit.
//
// Simple cubic parallel-bond lattice, spacing d, bonds along the axes with normal and shear
// stiffness k_n, k_s (N/m). A uniform strain stretches each axial bond by d eps_ii and shears it
// by d gamma_ij / 2 (particles do not rotate: the moments of the bonds along i and j cancel),
// one bond of each direction per cell volume d^3 and cross-section d^2:
//   C11 = C22 = C33 = k_n / d,   C12 = C13 = C23 = 0,   C44 = C55 = C66 = k_s / (2 d)   (Pa)
// (Voigt order xx, yy, zz, yz, xz, xy, engineering shear strains). For the thesis' PBM with
// k_n = E_b pi r^2 / (2 r) this is C11 = pi E_b / 4 (README: E = 3.1416 GPa at E_b = 4 GPa).
#include <array>
#include <string>

namespace dembridge::coupling
{
using Voigt6x6 = std::array<double, 36>; ///< row-major, Pa

Voigt6x6 simple_cubic_tensor(double kn, double ks, double spacing);

/// Throws std::runtime_error "<where>: ..." if C is not symmetric positive definite.
void check_positive_definite(const Voigt6x6& C, const std::string& where);

/// `stiffness_tensor` (6x6, Pa) of an elasticity.json written by `dembridge elasticity`.
Voigt6x6 read_elasticity_json(const std::string& file, const std::string& where);
} // namespace dembridge::coupling
