// Unit checks of the unified bond law: objectivity under rigid motion (large angles too),
// momentum balance, and agreement with the thesis' 12x12 Timoshenko matrix.
#include "dem/bonds/bond_kernel.h"
#include "dem/bonds/bond_matrix.h"
#include "dem/bonds/bond_model.h"
#include "dem/bonds/bonding.h"
#include "dem/solvers/explicit_solver.h"
#include "dem/solvers/time_step.h"
#include <gtest/gtest.h>
#include <random>

using namespace dembridge::dem;

namespace
{
BondMaterial material(BondModel m)
{
  BondMaterial mat;
  mat.model = m;
  mat.youngs_modulus = 4e9;
  mat.poisson_ratio = 0.3;
  return mat;
}

struct Pair
{
  Vec3 xa{0.1, -0.2, 0.3}, xb;
  double ra = 0.1, rb = 0.17; // polydisperse: PBM contact point off-centre
  BondConstants c;
  explicit Pair(BondModel m)
  {
    const Vec3 axis = Vec3(1, 2, -0.5).normalized();
    xb = xa + 0.27 * axis;
    const BondStiffness k = bond_stiffness(material(m), 0.27, ra, rb);
    c = {0.27, axis, k.kn, k.ks, k.ktor, k.kben, k.contact_fraction, 0, 0};
  }
  BondKinematics at(const Vec3& ua, const Vec3& ub, const Quat& qa, const Quat& qb) const
  {
    return {xa + ua, xb + ub, qa, qb, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  }
};

Quat rotation(double angle, Vec3 axis)
{
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

double scale(const BondResult& r, const BondConstants& c)
{
  return std::max({r.Fa.norm(), r.Fb.norm(), r.Ma.norm() / c.L0, r.Mb.norm() / c.L0, 1e-300});
}
} // namespace

class BondLaw : public ::testing::TestWithParam<BondModel>
{
};

// A bonded pair moved and rotated rigidly, by up to 3 rad, carries no bond force.
TEST_P(BondLaw, RigidMotionCarriesNoForce)
{
  const Pair pair(GetParam());
  const Vec3 centre = 0.5 * (pair.xa + pair.xb);
  for (double angle : {1e-3, 0.3, 1.5, 3.0})
    for (const Vec3& axis : {Vec3(0, 0, 1), Vec3(1, 1, 0), Vec3(-0.3, 0.7, 2.0)})
    {
      const Quat R = rotation(angle, axis);
      const Vec3 shift(5.0, -3.0, 2.0);
      const Vec3 ua = R * (pair.xa - centre) + centre + shift - pair.xa;
      const Vec3 ub = R * (pair.xb - centre) + centre + shift - pair.xb;
      const BondResult r = evaluate_bond(pair.at(ua, ub, R, R), pair.c);
      // a 1 mm strain of this bond gives kn * 1e-3 * L0: compare against that force scale
      const double ref = pair.c.kn * 1e-3 * pair.c.L0;
      EXPECT_LT(r.Fb.norm(), 1e-9 * ref) << "angle " << angle;
      EXPECT_LT(r.Mb.norm(), 1e-9 * ref * pair.c.L0) << "angle " << angle;
      EXPECT_LT(r.strain_energy, 1e-15 * ref * pair.c.L0);
    }
}

// Forces on the pair sum to zero and so do the moments about the origin, for an arbitrary
// (finite) deformation.
TEST_P(BondLaw, ForcesAndMomentsBalance)
{
  const Pair pair(GetParam());
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial)
  {
    const Vec3 ua = 0.01 * Vec3(u(rng), u(rng), u(rng)), ub = 0.01 * Vec3(u(rng), u(rng), u(rng));
    const Quat qa = rotation(0.05 * u(rng), Vec3(u(rng), u(rng), u(rng)));
    const Quat qb = rotation(0.05 * u(rng), Vec3(u(rng), u(rng), u(rng)));
    const BondKinematics k = pair.at(ua, ub, qa, qb);
    const BondResult r = evaluate_bond(k, pair.c);
    const double s = scale(r, pair.c);
    EXPECT_LT((r.Fa + r.Fb).norm(), 1e-12 * s);
    const Vec3 moment = k.xa.cross(r.Fa) + r.Ma + k.xb.cross(r.Fb) + r.Mb;
    EXPECT_LT(moment.norm(), 1e-12 * s * (k.xa.norm() + k.xb.norm() + pair.c.L0));
  }
}

// For small deformation the kernel's particle forces equal -K u with K the linearised unified
// matrix (rotated into the bond frame). The central difference (f(u) - f(-u)) / 2 cancels the
// second-order terms, so the kernel's first-order part is compared to 1e-9 (third-order terms
// ~1e-10 at eps = 1e-5, round-off ~1e-11).
TEST_P(BondLaw, KernelEqualsLinearisedMatrix)
{
  const Pair pair(GetParam());
  BondStiffness k;
  k.kn = pair.c.kn, k.ks = pair.c.ks, k.ktor = pair.c.ktor, k.kben = pair.c.kben;
  k.contact_fraction = pair.c.s;
  const Matrix12 K = unified_bond_matrix(k, pair.c.L0);
  const Eigen::Matrix3d R = bond_frame(pair.c.e0); // local -> global
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const double eps = 1e-5;
  // the kernel's particle forces in the bond frame for the local displacement vector u
  auto forces = [&](const Vector12& local)
  {
    const Vec3 ua = R * local.segment<3>(0), ta = R * local.segment<3>(3);
    const Vec3 ub = R * local.segment<3>(6), tb = R * local.segment<3>(9);
    const Quat qa(Eigen::AngleAxisd(ta.norm(), ta.normalized()));
    const Quat qb(Eigen::AngleAxisd(tb.norm(), tb.normalized()));
    const BondResult r = evaluate_bond(pair.at(ua, ub, qa, qb), pair.c);
    Vector12 f;
    f << R.transpose() * r.Fa, R.transpose() * r.Ma, R.transpose() * r.Fb, R.transpose() * r.Mb;
    return f;
  };
  for (int trial = 0; trial < 10; ++trial)
  {
    Vector12 local;
    for (int i = 0; i < 12; ++i)
      local[i] = eps * u(rng) * (i % 6 < 3 ? pair.c.L0 : 1.0);
    const Vector12 f = 0.5 * (forces(local) - forces(-local));
    const Vector12 expected = -K * local;
    EXPECT_LT((f - expected).norm(), 1e-9 * expected.norm()) << "trial " << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(AllModels, BondLaw,
                         ::testing::Values(BondModel::parallel_bond, BondModel::euler_bernoulli,
                                           BondModel::timoshenko));

// The unified TBBM (Table 9 stiffnesses, contact point at the beam centre) is the thesis'
// Timoshenko beam matrix (eq. 26-31), for stocky and slender bonds.
TEST(TimoshenkoMatrix, UnifiedLawEqualsThesisMatrix)
{
  for (double L : {0.05, 0.2, 2.0})
  {
    const BondStiffness k = bond_stiffness(material(BondModel::timoshenko), L, 0.1, 0.1);
    const Matrix12 unified = unified_bond_matrix(k, L);
    const Matrix12 thesis = timoshenko_beam_matrix(4e9, 0.3, 0.1, L);
    EXPECT_LT((unified - thesis).norm(), 1e-12 * thesis.norm()) << "L = " << L;
  }
}

// Paper Table 5 (case 3): bond stiffnesses in GPa·m for 1 and 10 bonds over 4 m.
TEST(BondStiffness, MatchesPaperTable5)
{
  BondMaterial m = material(BondModel::timoshenko);
  m.youngs_modulus = 200e9;
  auto k = [&](BondModel model, double L)
  {
    m.model = model;
    return bond_stiffness(m, L, 0.2, 0.2);
  };
  EXPECT_NEAR(k(BondModel::timoshenko, 4.0).kn / 1e9, 6.283, 0.001);
  EXPECT_NEAR(k(BondModel::parallel_bond, 4.0).ks / 1e9, 2.416, 0.001);
  EXPECT_NEAR(k(BondModel::euler_bernoulli, 4.0).ks / 1e9, 0.04712, 0.00001);
  EXPECT_NEAR(k(BondModel::timoshenko, 4.0).ks / 1e9, 0.04612, 0.00001);
  EXPECT_NEAR(k(BondModel::parallel_bond, 0.4).ks / 1e9, 24.17, 0.01);
  EXPECT_NEAR(k(BondModel::euler_bernoulli, 0.4).ks / 1e9, 47.12, 0.01);
  EXPECT_NEAR(k(BondModel::timoshenko, 0.4).ks / 1e9, 14.88, 0.01);
}

// A free pair spinning about an axis across the bond keeps its length up to the centrifugal
// stretch m w^2 r / k_n and conserves energy (no spurious forces from the rotation).
TEST(RigidRotation, SpinningPairStaysRigidOverManyTurns)
{
  ParticleStore p;
  p.add(Vec3(0, 0, 0), 0.1, 2500);
  p.add(Vec3(0.2, 0, 0), 0.1, 2500);
  BondStore b;
  form_bonds(p, b, material(BondModel::timoshenko), 1.0);
  ASSERT_EQ(b.size(), 1u);
  const double omega = 50.0; // rad/s about z through the centre
  const Vec3 w(0, 0, omega);
  for (int i = 0; i < 2; ++i)
  {
    p.velocity[i] = w.cross(p.position[i] - Vec3(0.1, 0, 0));
    p.angular_velocity[i] = w;
  }
  const double dt = 0.5 * estimate_critical_time_step(p, b).critical();
  ExplicitSolver s(p, b, {}, {}, {}, {dt, 0, 1});
  const long steps = long(6 * 2 * M_PI / omega / dt); // six turns
  double max_stretch = 0;
  for (long n = 0; n < steps; ++n)
  {
    s.step(n % 100 == 0);
    max_stretch = std::max(max_stretch, std::abs((p.position[1] - p.position[0]).norm() - 0.2));
  }
  s.step(true);
  const double centrifugal = p.mass[0] * omega * omega * 0.1 / b.kn[0];
  EXPECT_LT(max_stretch, 3 * centrifugal + 1e-12);
  EXPECT_LT(s.energy().relative_error(), 1e-3);
}
