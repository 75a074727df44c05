// The packing's own stiffness tensor (dem/measurements/elasticity_tensor.h) against
// closed forms and a published value:
//  - the simple cubic PBM lattice: C11 = k_n/d, C12 = 0, C44 = k_s/(2d) (elasticity_tensor.h,
//    item 3), measured on a finite block (1e-6 of C11) and from the periodic cell (1e-12);
//  - the HCP lattice: transversely isotropic about its stacking axis z (hexagonal symmetry),
//    exactly for the periodic cell, within the boundary layer's trace for a finite block;
//  - the periodic HCP cell's E_x: Wang & Mora (2008), thesis eq. 2, 5.843 GPa for the thesis'
//    PBM micro-parameters (k̄_n = E_b / (2 r), k_n / k_s = 4.2), within 0.01 %;
//  - every tensor symmetric and positive definite.
#include "dem/measurements/elasticity_tensor.h"
#include <Eigen/Eigenvalues>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <numbers>

using namespace dembridge::dem;

namespace
{
/// The thesis' PBM (examples/compression_hcp.prm): E_b = 4 GPa, k̄_n = E_b / (2 r), kappa = 4.2.
BondMaterial thesis_pbm()
{
  BondMaterial m;
  m.model = BondModel::parallel_bond;
  m.youngs_modulus = 4e9;
  m.poisson_ratio = 0.3;
  m.stiffness_ratio = 4.2;
  return m;
}

CaseConfig lattice_case(ParticleSource::Kind kind, double r, const Vec3& box)
{
  CaseConfig c;
  c.particles.kind = kind;
  c.particles.radius = r;
  c.particles.box_size = box;
  c.bonds.material = thesis_pbm();
  c.run.static_solver = true;
  return c;
}

double max_relative(const Matrix6& a, const Matrix6& b, double scale)
{
  return (a - b).cwiseAbs().maxCoeff() / scale;
}

void print(const std::string& what, const Matrix6& C)
{
  std::cout << what << " (GPa):\n"
            << (C / 1e9).format(Eigen::IOFormat(6, 0, " ", "\n", "  ")) << "\n";
}

/// Deviations from transverse isotropy about z, relative to C11: C11 = C22, C13 = C23,
/// C44 = C55, C66 = (C11 - C12)/2, and the entries that must vanish.
struct TransverseIsotropy
{
  double c11_c22, c13_c23, c44_c55, c66, zeros;
};
TransverseIsotropy transverse_isotropy(const Matrix6& C)
{
  const double s = C(0, 0);
  double zeros = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
    {
      const bool allowed = (i < 3 && j < 3) || i == j;
      if (!allowed)
        zeros = std::max(zeros, std::abs(C(i, j)) / s);
    }
  return {std::abs(C(0, 0) - C(1, 1)) / s, std::abs(C(0, 2) - C(1, 2)) / s,
          std::abs(C(3, 3) - C(4, 4)) / s, std::abs(C(5, 5) - 0.5 * (C(0, 0) - C(0, 1))) / s,
          zeros};
}

void expect_symmetric_positive_definite(const Matrix6& C, double tolerance)
{
  EXPECT_LT((C - C.transpose()).cwiseAbs().maxCoeff() / C.cwiseAbs().maxCoeff(), tolerance);
  const Eigen::SelfAdjointEigenSolver<Matrix6> eig(0.5 * (C + C.transpose()));
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
}

/// Wang & Mora (2008), thesis eq. 2: E_x of the ideal HCP lattice, and eq. 3: E_z.
double wang_mora_ex(double kn, double ks, double r)
{
  return 3 * std::sqrt(2.0) * kn * (kn + ks) * (3 * kn * kn + 23 * ks * ks + 22 * kn * ks) /
         (r * (18 * kn * kn * kn + 119 * kn * kn * ks + 128 * kn * ks * ks + 23 * ks * ks * ks));
}
double wang_mora_ez(double kn, double ks, double r)
{
  return 3 * std::sqrt(2.0) * kn * (kn + ks) / (r * (5 * kn + ks));
}
} // namespace

TEST(ElasticityTensor, SimpleCubicClosedForm)
{
  const double r = 0.005;
  const BondStiffness k = bond_stiffness(thesis_pbm(), 2 * r, r, r);
  const Matrix6 C = simple_cubic_stiffness(k.kn, k.ks, 2 * r);
  EXPECT_NEAR(C(0, 0), std::numbers::pi * 4e9 / 4, 1e-6 * C(0, 0)); // pi E_b / 4
  EXPECT_NEAR(C(3, 3), C(0, 0) / (2 * 4.2), 1e-12 * C(0, 0));       // k_s / (2d)
  const ElasticProperties p = elastic_properties(C);
  EXPECT_NEAR(p.youngs_modulus.x(), C(0, 0), 1e-12 * C(0, 0)); // C12 = 0: E = C11, nu = 0
  EXPECT_NEAR(p.poisson_ratio(0, 1), 0.0, 1e-15);
  EXPECT_NEAR(p.shear_modulus.z(), C(5, 5), 1e-12 * C(5, 5));
  EXPECT_NEAR(p.zener_ratio, 1 / 4.2, 1e-12); // 2 C44 / (C11 - C12) = k_s / k_n
  // isotropic input: A^U = 0, Zener 1, E and nu back
  const double E = 3e9, nu = 0.25, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)),
               mu = E / (2 * (1 + nu));
  Matrix6 iso = Matrix6::Zero();
  iso.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i)
    iso(i, i) += 2 * mu, iso(3 + i, 3 + i) = mu;
  const ElasticProperties q = elastic_properties(iso);
  EXPECT_NEAR(q.universal_anisotropy, 0.0, 1e-12);
  EXPECT_NEAR(q.zener_ratio, 1.0, 1e-12);
  EXPECT_NEAR(q.youngs_modulus.y(), E, 1e-12 * E);
  EXPECT_NEAR(q.poisson_ratio(2, 0), nu, 1e-12);
  EXPECT_GT(p.universal_anisotropy, 0.1); // the cubic lattice is far from isotropic
}

TEST(ElasticityTensor, PeriodicSimpleCubicEqualsClosedForm)
{
  for (BondModel model : {BondModel::parallel_bond, BondModel::timoshenko})
  {
    BondMaterial mat = thesis_pbm();
    mat.model = model;
    const double r = 0.005;
    const PeriodicElasticity p =
        periodic_stiffness_tensor(lattice_cell(ParticleSource::Kind::cubic, r), mat);
    const Matrix6 exact = simple_cubic_stiffness(mat, r);
    EXPECT_EQ(p.n_bonds_per_cell, 3);
    EXPECT_LT(max_relative(p.properties.stiffness, exact, exact(0, 0)), 1e-12);
  }
}

TEST(ElasticityTensor, MeasuredSimpleCubicEqualsClosedForm)
{
  const double r = 0.005;
  for (BondModel model : {BondModel::parallel_bond, BondModel::timoshenko})
  {
    CaseConfig c = lattice_case(ParticleSource::Kind::cubic, r, Vec3(0.08, 0.07, 0.09));
    c.bonds.material.model = model;
    const Model m = build_model(c);
    const MeasuredElasticity e = measured_stiffness_tensor(m);
    const Matrix6 exact = simple_cubic_stiffness(c.bonds.material, r);
    print("simple cubic, measured", e.properties.stiffness);
    const double error = max_relative(e.raw_stiffness, exact, exact(0, 0));
    std::cout << "max |C - closed form| / C11 = " << error << ", core " << e.n_core
              << " particles, " << e.solve_seconds << " s\n";
    EXPECT_LT(error, 1e-6);
    // core box on the lattice's cell boundaries: 8 x 7 x 9 cells minus 2 on each side
    EXPECT_EQ(e.n_core, 4 * 3 * 5);
    EXPECT_NEAR(e.core_volume, 4 * 3 * 5 * std::pow(2 * r, 3), 1e-12 * e.core_volume);
    expect_symmetric_positive_definite(e.raw_stiffness, 1e-9);
  }
}

TEST(ElasticityTensor, PeriodicHcpWangMora)
{
  const double r = 0.005;
  const BondMaterial mat = thesis_pbm();
  const PeriodicElasticity p =
      periodic_stiffness_tensor(lattice_cell(ParticleSource::Kind::hcp, r), mat);
  const Matrix6& C = p.properties.stiffness;
  print("HCP, periodic cell", C);
  EXPECT_EQ(p.n_basis, 2);
  EXPECT_NEAR(p.mean_coordination, 12.0, 1e-12);
  EXPECT_NEAR(p.cell_volume, 2 * 4 * std::sqrt(2.0) * r * r * r, 1e-12 * p.cell_volume);
  const BondStiffness k = bond_stiffness(mat, 2 * r, r, r);
  const double ex = p.properties.youngs_modulus.x(), ez = p.properties.youngs_modulus.z();
  std::cout << "E_x = " << ex << " Pa (eq. 2: " << wang_mora_ex(k.kn, k.ks, r) << "), E_z = " << ez
            << " Pa (eq. 3: " << wang_mora_ez(k.kn, k.ks, r) << ")\n";
  EXPECT_NEAR(ex, 5.843e9, 1e-4 * 5.843e9); // thesis: 5.843 GPa (0.01 %)
  EXPECT_NEAR(ex, wang_mora_ex(k.kn, k.ks, r), 1e-9 * ex);
  EXPECT_NEAR(ez, wang_mora_ez(k.kn, k.ks, r), 1e-9 * ez);
  const TransverseIsotropy t = transverse_isotropy(C);
  EXPECT_LT(t.c11_c22, 1e-9);
  EXPECT_LT(t.c13_c23, 1e-9);
  EXPECT_LT(t.c44_c55, 1e-9);
  EXPECT_LT(t.c66, 1e-9);
  EXPECT_LT(t.zeros, 1e-9);
  expect_symmetric_positive_definite(C, 1e-12);
}

TEST(ElasticityTensor, PeriodicFccIsCubicAboutItsCubeAxes)
{
  // packings.cc stacks the close-packed layers normal to z with rows along x: x = [1-10]/sqrt2,
  // y = [-1-12]/sqrt6, z = [111]/sqrt3 in cube axes (the interlayer neighbour (r, r/sqrt3, dz)
  // is then sqrt2 r (1, 0, 1), an fcc neighbour). Rotated to the cube axes the tensor must have
  // cubic symmetry: C11 = C22 = C33, C12 = C13 = C23, C44 = C55 = C66, nothing else.
  const double r = 0.005;
  const PeriodicElasticity p =
      periodic_stiffness_tensor(lattice_cell(ParticleSource::Kind::fcc, r), thesis_pbm());
  EXPECT_EQ(p.n_basis, 1);
  EXPECT_NEAR(p.mean_coordination, 12.0, 1e-12);
  EXPECT_NEAR(p.cell_volume, 4 * std::sqrt(2.0) * r * r * r, 1e-12 * p.cell_volume);
  Eigen::Matrix3d Q; // columns: the layer frame's axes in cube axes
  Q.col(0) = Vec3(1, -1, 0) / std::sqrt(2.0);
  Q.col(1) = Vec3(-1, -1, 2) / std::sqrt(6.0);
  Q.col(2) = Vec3(1, 1, 1) / std::sqrt(3.0);
  const Matrix6 C = rotate_stiffness(p.properties.stiffness, Q);
  print("FCC, periodic cell, cube axes", C);
  const double s = C(0, 0);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_NEAR(C(i, i), C(0, 0), 1e-9 * s);
    EXPECT_NEAR(C(3 + i, 3 + i), C(3, 3), 1e-9 * s);
    EXPECT_NEAR(C(i, (i + 1) % 3), C(0, 1), 1e-9 * s);
  }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
    {
      if (!((i < 3 && j < 3) || i == j))
      {
        EXPECT_NEAR(C(i, j), 0.0, 1e-9 * s);
      }
    }
  // A rotation changes neither the invariants nor the anisotropy index.
  EXPECT_NEAR(elastic_properties(C).universal_anisotropy, p.properties.universal_anisotropy, 1e-9);
  expect_symmetric_positive_definite(C, 1e-12);
}

/// The finite HCP block's tensor: a cube of 0.1 m (r = 5 mm, 1224 spheres), core margin 2
/// diameters, the core box cut to whole lattice periods.
MeasuredElasticity hcp_block(double side, double margin)
{
  const double r = 0.005;
  const Model m = build_model(lattice_case(ParticleSource::Kind::hcp, r, Vec3::Constant(side)));
  ElasticityMeasurementSettings s;
  s.core_margin = margin;
  s.core_period = lattice_axis_periods(ParticleSource::Kind::hcp, r);
  return measured_stiffness_tensor(m, s);
}

TEST(ElasticityTensor, MeasuredHcpIsTransverselyIsotropic)
{
  // The held boundary imposes the affine field with the sublattice shifts and rotations
  // unrelaxed; the core relaxes, and the trace of that boundary layer left in the core is what
  // separates the finite block from the ideal lattice. Measured (tests below and the study in
  // the commit log): the core of the 0.1 m cube differs from the periodic cell by at most 0.7 %
  // of C11 and from transverse isotropy by at most 0.21 % of C11 (C44 vs C55), and both shrink
  // as the core moves away from the boundary. Tolerances: 0.5 % of C11 for each transverse-
  // isotropy relation, 1 % of C11 from the periodic cell, 1 % raw asymmetry (measured 0.34 %).
  const MeasuredElasticity e = hcp_block(0.1, 2.0);
  const Matrix6& C = e.properties.stiffness;
  print("HCP, measured (0.1 m cube)", C);
  const TransverseIsotropy t = transverse_isotropy(C);
  std::cout << "transverse isotropy residuals / C11: " << t.c11_c22 << " " << t.c13_c23 << " "
            << t.c44_c55 << " " << t.c66 << " " << t.zeros << "; raw asymmetry " << e.symmetry_error
            << ", core strain deviation " << e.core_strain_deviation << "\n";
  EXPECT_LT(t.c11_c22, 5e-3);
  EXPECT_LT(t.c13_c23, 5e-3);
  EXPECT_LT(t.c44_c55, 5e-3);
  EXPECT_LT(t.c66, 5e-3);
  EXPECT_LT(t.zeros, 5e-3);
  const PeriodicElasticity p =
      periodic_stiffness_tensor(lattice_cell(ParticleSource::Kind::hcp, 0.005), thesis_pbm());
  const double from_periodic = max_relative(C, p.properties.stiffness, C(0, 0));
  std::cout << "max |C - C_periodic| / C11 = " << from_periodic << "\n";
  EXPECT_LT(from_periodic, 1e-2);
  EXPECT_LT(e.symmetry_error, 1e-2);
  expect_symmetric_positive_definite(e.raw_stiffness, 1e-2);
  // the core holds exactly its share of the lattice: ideal HCP solid fraction pi / (3 sqrt 2)
  const double solid = e.n_core * 4.0 / 3.0 * std::numbers::pi * std::pow(0.005, 3);
  EXPECT_NEAR(solid / e.core_volume, std::numbers::pi / (3 * std::sqrt(2.0)), 1e-9);
}

TEST(ElasticityTensor, MeasuredHcpConvergesOnThePeriodicCell)
{
  // A 0.14 m cube: the core 1, then 3 diameters from the faces. Measured: C11 2.3 % then 0.36 %
  // below the periodic cell's; the deeper core must be at least three times closer.
  const PeriodicElasticity p =
      periodic_stiffness_tensor(lattice_cell(ParticleSource::Kind::hcp, 0.005), thesis_pbm());
  const Matrix6& P = p.properties.stiffness;
  const double near = max_relative(hcp_block(0.14, 1.0).properties.stiffness, P, P(0, 0));
  const double deep = max_relative(hcp_block(0.14, 3.0).properties.stiffness, P, P(0, 0));
  std::cout << "max |C - C_periodic| / C11: margin 1: " << near << ", margin 3: " << deep << "\n";
  EXPECT_LT(deep, near / 3);
  EXPECT_LT(deep, 5e-3);
}

TEST(ElasticityTensor, BadInput)
{
  // a block too small for its core: one-line InputError naming the reason
  const Model m =
      build_model(lattice_case(ParticleSource::Kind::cubic, 0.005, Vec3::Constant(0.04)));
  try
  {
    measured_stiffness_tensor(m);
    ADD_FAILURE() << "no error";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("has no core"), std::string::npos) << e.what();
  }
  Matrix6 C = simple_cubic_stiffness(1e6, 1e5, 0.01);
  C(3, 3) = -C(3, 3);
  EXPECT_THROW(elastic_properties(C, "test"), InputError);
  EXPECT_THROW(lattice_cell(ParticleSource::Kind::random, 0.005), InputError);
  BondMaterial none = thesis_pbm();
  EXPECT_THROW(
      periodic_stiffness_tensor(lattice_cell(ParticleSource::Kind::cubic, 0.005), none, 0.9),
      InputError); // no neighbour within 0.9 (R_a + R_b)
}
