#pragma once
// The packing's own linear-elastic stiffness tensor: what a continuum must be given to
// stand for a bonded packing (the coupled mode's FE side, `dembridge verify`).
//
// Voigt notation throughout: order xx, yy, zz, yz, xz, xy; engineering shear strains
// (gamma_yz = 2 eps_yz), so sigma_I = C_IJ eps_J and the strain energy density is
// w = 1/2 eps^T C eps (Pa). Tension positive.
//
// 1. measured_stiffness_tensor(model): a finite specimen under six uniform strains. Each unit
//    strain eps^(J) is applied as the affine field u = E x (E the 3x3 strain tensor; its rotation
//    is zero for a symmetric E, so rotations are held at 0) prescribed on the boundary particles
//    (centres within t r of a face of the specimen's extent, the face groups' convention); every
//    other particle relaxes (translations and rotations) in one static solve (static_solver.h).
//    Stress: the RVE average of thesis eq. 54 over the core, the particles whose centres lie at
//    least m from every face of the extent, divided by the volume of the core box,
//        sigma = (1 / V_core) sum_{p in core} V_p sigma^(p)        (thesis eq. 54, 59-62),
//    sigma^(p) the small-strain particle stress (particle_stress.h), symmetrised. Strain: the
//    core's own, the symmetric part of the least-squares gradient of its particles'
//    displacements. With S and E the 6x6 matrices of the six stresses and strains (columns),
//        C = S E^-1,
//    symmetrised (the raw asymmetry is reported).
//    Why the core, and its own strain. The reactions' virial (1/V) sum f x over the held
//    particles equals the sum of d (x) F over all bonds, and a block of n_x n_y n_z cubic cells
//    holds (n_x - 1) n_y n_z bonds along x: the block is softer by 1/n per direction, so no
//    single volume V gives the lattice's tensor (only a cube, with the odd V = (n - 1) n^2 d^3).
//    In the core every particle has its full set of bonds. The held layer, moved affinely with
//    the sublattice shifts and rotations of a lattice like HCP unrelaxed, is stiffer than the
//    bulk and takes less than its share of the imposed strain: the HCP core's strain differs by
//    9-20 % from the boundary's (specimens of 6-14 diameters), so the core's own strain is the one
//    to divide by. The core box is cut to whole lattice periods (core_period) for lattices, so that
//    it holds exactly its share of particles (a box cutting a lattice anywhere miscounts by up to
//    a layer per face: 3-13 % on these specimens). For the simple cubic lattice the core box, m
//    a whole number of spacings, is a union of the particles' cells and the displacement field
//    is affine everywhere, so the measurement gives C11 = k_n/d, C12 = 0, C44 = k_s/(2d) to
//    solver round-off (1e-12, tests/dem/test_elasticity_tensor). For other packings the core
//    converges to the bulk as the boundary's trace decays (HCP: 0.6 % of C11 from the periodic
//    cell on a 10-diameter cube, core margin 2 diameters; 0.36 % on 14 diameters, margin 3).
//
// 2. periodic_stiffness_tensor(cell, material): the ideal infinite lattice from one periodic
//    cell. Particle p of the basis in the cell shifted by the lattice vector R moves by
//        u = E (x_p + R) + w_p,   rotation theta_p,
//    the same w_p (sublattice shift) and theta_p in every cell. With z = (w, theta) of the basis
//    (w of particle 0 held: the rigid translation) and the cell's bonds' 12x12 matrices
//    (bond_matrix.h, global frame) assembled over these DOFs, the strain energy per cell is
//    W = 1/2 [e; z]^T K [e; z]; minimising over z (static condensation),
//        C = (1 / V_cell) (K_ee - K_ez K_zz^-1 K_ze),
//    V_cell = |det(a1, a2, a3)|. No boundary at all: for the HCP lattice loaded in a close-packed
//    layer this is Wang and Mora's (2008) E_x (thesis eq. 2) with no extrapolation over specimens.
//
// 3. simple_cubic_stiffness(k_n, k_s, d): the closed form of the simple cubic lattice with
//    bonds at mid-spacing (the PBM, and the beam bonds, between equal spheres): under a uniform
//    strain every bond deforms affinely and the particles do not rotate (by the lattice's
//    inversion symmetry), so each cell (volume d^3, three bonds) stores
//        W = 1/2 k_n d^2 (e_xx^2 + e_yy^2 + e_zz^2) + 1/4 k_s d^2 (g_yz^2 + g_xz^2 + g_xy^2):
//        C11 = C22 = C33 = k_n / d,  C12 = C13 = C23 = 0,  C44 = C55 = C66 = k_s / (2 d).
//    For the thesis' PBM (k_n = (E_b / 2r) pi r^2, d = 2r): C11 = pi E_b / 4.
//
// 4. elastic_properties(C): engineering constants from the compliance S = C^-1:
//    E_i = 1 / S_ii, nu_ij = -S_ji / S_ii (lateral strain along j over axial strain along i in
//    uniaxial stress along i), G_yz = 1 / S_44, G_xz = 1 / S_55, G_xy = 1 / S_66; Voigt and Reuss
//    bulk and shear moduli and the universal anisotropy index (Ranganathan & Ostoja-Starzewski
//    2008, Phys. Rev. Lett. 101, 055504, eq. 6)
//        A^U = 5 G_V / G_R + K_V / K_R - 6   (0 for isotropy, > 0 otherwise),
//    and the Zener ratio A = 2 C44 / (C11 - C12) of the axis-averaged constants (cubic symmetry;
//    1 for isotropy).
#include "dem/model/case_config.h"
#include "dem/model/model.h"
#include "dem/solvers/static_solver.h"
#include <Eigen/Dense>
#include <vector>

namespace dembridge::dem
{
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

/// Engineering constants and anisotropy measures of a stiffness tensor (see 4. above).
struct ElasticProperties
{
  Matrix6 stiffness = Matrix6::Zero();                     ///< C, Pa
  Matrix6 compliance = Matrix6::Zero();                    ///< S = C^-1, 1/Pa
  Vec3 youngs_modulus = Vec3::Zero();                      ///< E_x, E_y, E_z (Pa)
  Eigen::Matrix3d poisson_ratio = Eigen::Matrix3d::Zero(); ///< nu_ij = -S_ji / S_ii; diagonal 0
  Vec3 shear_modulus = Vec3::Zero();                       ///< G_yz, G_xz, G_xy (Pa)
  double bulk_modulus_voigt = 0, bulk_modulus_reuss = 0;   ///< K_V, K_R (Pa)
  double shear_modulus_voigt = 0, shear_modulus_reuss = 0; ///< G_V, G_R (Pa)
  double universal_anisotropy = 0;                         ///< A^U = 5 G_V / G_R + K_V / K_R - 6
  double zener_ratio = 0; ///< 2 C44 / (C11 - C12), axis-averaged constants
};

/// Properties of C; throws InputError ("<where>: ...") if C is not symmetric positive definite
/// (symmetry to 1e-9 of its largest entry).
ElasticProperties elastic_properties(const Matrix6& C, const std::string& where = "stiffness");

/// Closed form of the simple cubic lattice with mid-spacing bonds (see 3. above): spacing d (m),
/// bond stiffnesses k_n, k_s (N/m).
Matrix6 simple_cubic_stiffness(double normal_stiffness, double shear_stiffness, double spacing);
/// The same for a simple cubic lattice of spheres of radius r (d = 2r) with bonds of `material`.
Matrix6 simple_cubic_stiffness(const BondMaterial& material, double radius);

/// The tensor in rotated axes: C'_ijkl = Q_ia Q_jb Q_kc Q_ld C_abcd, Q the rotation whose
/// columns are the old axes in the new ones (v_new = Q v_old).
Matrix6 rotate_stiffness(const Matrix6& C, const Eigen::Matrix3d& Q);

/// The 3x3 strain tensor of a Voigt strain vector (engineering shears halved).
Eigen::Matrix3d strain_tensor(const Vector6& voigt_strain);
/// The Voigt vector of a (symmetric part of a) 3x3 stress tensor.
Vector6 voigt_stress(const Eigen::Matrix3d& stress);

struct ElasticityMeasurementSettings
{
  double strain = 1e-4;            ///< magnitude of each of the six unit strains (linear: any)
  double boundary_thickness = 1.5; ///< held: centres within this many radii of a face
  /// Core: centres at least this many mean particle diameters from every face of the extent.
  /// A whole number keeps a simple cubic lattice's core box on its cell boundaries (exact).
  double core_margin = 2.0;
  /// Lattice periods along the axes (m; lattice_axis_periods), 0: none (random packings). The
  /// core box's sides are then cut to whole periods, so that it holds exactly the particles
  /// whose volume it is (a box cutting a lattice anywhere miscounts by up to a layer per face).
  Vec3 core_period = Vec3::Zero();
  StaticSettings solver = []
  {
    StaticSettings s;
    s.cg_tolerance = 1e-12;
    return s;
  }();
};

struct MeasuredElasticity
{
  ElasticProperties properties;            ///< of the symmetrised tensor
  Matrix6 raw_stiffness = Matrix6::Zero(); ///< S E^-1 before symmetrisation
  double symmetry_error = 0;               ///< max |C_IJ - C_JI| / max |C_IJ| of the raw tensor
  double stress_asymmetry = 0; ///< max over the six of |sigma - sigma^T| / |sigma| (core)
  /// max |eps_core - eps_applied| / |eps_applied|: how far the boundary layer shifts the core's
  /// strain from the one applied on the boundary (0 for a simple cubic lattice)
  double core_strain_deviation = 0;
  Vec3 extent_lo = Vec3::Zero(), extent_hi = Vec3::Zero(); ///< specimen extent (m)
  Vec3 core_lo = Vec3::Zero(), core_hi = Vec3::Zero();     ///< the RVE box (m)
  double core_volume = 0;                                  ///< V_core (m^3)
  long n_particles = 0, n_bonds = 0, n_held = 0, n_core = 0;
  double solve_seconds = 0; ///< six static solves
  double max_residual = 0;  ///< largest relative residual of the six solves
};

/// The finite specimen's tensor (see 1. above). The model's own supports, loads and groups are
/// ignored. Throws InputError if the core or the boundary layer is empty, or the tensor is not
/// positive definite.
MeasuredElasticity measured_stiffness_tensor(const Model& model,
                                             const ElasticityMeasurementSettings& settings = {});

/// Periods of a lattice along x, y, z as packings.cc generates it: cubic (2r, 2r, 2r); hcp and
/// fcc (2r, sqrt3 r, 2 sqrt(2/3) r): a row, the row spacing, the layer spacing. Zero for
/// packings that are not lattices.
Vec3 lattice_axis_periods(ParticleSource::Kind kind, double radius);

/// One periodic cell of a lattice: lattice vectors (columns of `vectors`, m) and the basis.
struct LatticeCell
{
  Eigen::Matrix3d vectors = Eigen::Matrix3d::Identity();
  std::vector<Vec3> basis;
  std::vector<double> radius;
};

/// The cell of the lattices packings.cc generates, in the same orientation: cubic (spacing 2r),
/// hcp (close-packed rows along x, triangular layers normal to z, ABAB; two particles) and fcc
/// (the same layers ABC; one particle). Throws InputError for other kinds.
LatticeCell lattice_cell(ParticleSource::Kind kind, double radius);

struct PeriodicElasticity
{
  ElasticProperties properties;
  double cell_volume = 0;   ///< m^3
  int n_basis = 0;          ///< particles per cell
  int n_bonds_per_cell = 0; ///< bonds per cell (each counted once)
  double mean_coordination = 0;
};

/// The ideal lattice's tensor (see 2. above); bonds join basis particles and their images whose
/// centres lie within contact_radius_multiplier (R_a + R_b), as bond formation does. Throws
/// InputError if the cell has no bond or a mechanism (a relaxation costing no energy).
PeriodicElasticity periodic_stiffness_tensor(const LatticeCell& cell, const BondMaterial& material,
                                             double contact_radius_multiplier = 1.0);
} // namespace dembridge::dem
