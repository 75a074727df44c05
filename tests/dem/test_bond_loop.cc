// The optimised bond loop (SIMD blocks of bond_block.h, bonds in the solver's thread
// partition, particles in spatial order) against the scalar kernel of bond_kernel.h evaluated
// bond by bond: the same particle forces, moments, dashpot resultants, per-bond contact forces
// and strain energy to 1e-12 relative (only the order of floating-point sums and the compiler's
// fused multiply-adds differ), on an HCP lattice and a random packing, with and without
// dashpots, on 1 and 2 threads.
#include "dem/bonds/bond_block.h"
#include "dem/bonds/bond_kernel.h"
#include "dem/bonds/bonding.h"
#include "dem/measurements/particle_stress.h"
#include "dem/model/model.h"
#include "dem/solvers/explicit_solver.h"
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <random>

using namespace dembridge::dem;

namespace
{
/// A bonded specimen of r = 2.5 mm spheres in a small box, renumbered as every case is.
Model specimen(ParticleSource::Kind kind)
{
  CaseConfig c;
  c.particles.kind = kind;
  c.particles.radius = 2.5e-3;
  c.particles.box_size =
      kind == ParticleSource::Kind::random ? Vec3(0.04, 0.03, 0.03) : Vec3(0.035, 0.025, 0.025);
  c.particles.seed = 3;
  c.bonds.material.model = BondModel::timoshenko;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  c.bonds.contact_radius_multiplier = kind == ParticleSource::Kind::random ? 1.04 : 1.0;
  return build_model(c);
}

/// Seeded deformation: displacements of 1e-5 m, rotations of 2e-3 rad, velocities of 1 cm/s
/// and angular velocities of 1 rad/s, so that every term of the law is exercised.
void deform(ParticleStore& p, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    p.position[i] += 1e-5 * random();
    const Vec3 axis = random();
    p.orientation[i] = Quat(Eigen::AngleAxisd(2e-3 * axis.norm(), axis.normalized()));
    p.velocity[i] = 1e-2 * random();
    p.angular_velocity[i] = random();
  }
}

struct Reference
{
  std::vector<Vec3> F, M, Fd, Md;
  std::map<std::pair<int, int>, std::pair<Vec3, Vec3>> bond; // (a, b) -> contact force, couple
  double strain = 0;
};

/// The scalar kernel, bond by bond in the model's order.
template <bool dashpots> Reference scalar_kernel(const ParticleStore& p, const BondStore& b)
{
  Reference r;
  r.F.assign(p.size(), Vec3::Zero()), r.M = r.Fd = r.Md = r.F;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const int ia = b.a[k], ib = b.b[k];
    BondForces f;
    bond_law<dashpots>(p.position[ia].data(), p.position[ib].data(),
                       p.orientation[ia].coeffs().data(), p.orientation[ib].coeffs().data(),
                       p.velocity[ia].data(), p.velocity[ib].data(), p.angular_velocity[ia].data(),
                       p.angular_velocity[ib].data(),
                       {b.rest_length[k], b.rest_axis[k], b.kn[k], b.ks[k], b.ktor[k], b.kben[k],
                        b.contact_fraction[k], b.damping_force[k], b.damping_moment[k]},
                       f);
    bond_resultants(f.Fc, f.Mc, f, r.F[ia].data(), r.M[ia].data(), r.F[ib].data(), r.M[ib].data());
    bond_resultants(f.Fd, f.Md, f, r.Fd[ia].data(), r.Md[ia].data(), r.Fd[ib].data(),
                    r.Md[ib].data());
    r.bond[{ia, ib}] = {Vec3(f.Fc[0], f.Fc[1], f.Fc[2]), Vec3(f.Mc[0], f.Mc[1], f.Mc[2])};
    r.strain += f.strain_energy;
  }
  return r;
}

/// Largest |x - y| over the arrays, relative to the largest |y|.
double relative_difference(const std::vector<Vec3>& x, const std::vector<Vec3>& y)
{
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < y.size(); ++i)
    diff = std::max(diff, (x[i] - y[i]).norm()), scale = std::max(scale, y[i].norm());
  return diff / scale;
}

struct Case
{
  ParticleSource::Kind kind;
  double damping; ///< bond damping ratio (0: no dashpots)
  int threads;
};

// GoogleTest would otherwise print the struct's bytes, padding included, into the test list.
void PrintTo(const Case& c, std::ostream* os)
{
  *os << (c.kind == ParticleSource::Kind::hcp ? "hcp" : "random") << ", damping " << c.damping
      << ", " << c.threads << " threads";
}

class BondLoop : public ::testing::TestWithParam<Case>
{
};

TEST_P(BondLoop, OptimisedLoopEqualsTheScalarKernel)
{
  const Case c = GetParam();
  Model m = specimen(c.kind);
  ASSERT_GT(m.bonds.size(), 500u);
  assign_bond_damping(m.particles, m.bonds, c.damping);
  deform(m.particles, 17);
  const Reference ref = c.damping > 0 ? scalar_kernel<true>(m.particles, m.bonds)
                                      : scalar_kernel<false>(m.particles, m.bonds);
  ASSERT_GT(ref.strain, 0);

  ParticleStore p = m.particles;
  BondStore b = m.bonds; // the solver puts the bonds in its thread order
  ExplicitSolver solver(p, b, {}, {}, {}, {0.5 * m.critical.critical(), 0.0, c.threads});
  solver.evaluate_bond_forces();
  EXPECT_LT(relative_difference(p.force, ref.F), 1e-12);
  EXPECT_LT(relative_difference(p.torque, ref.M), 1e-12);
  EXPECT_NEAR(solver.energy().strain, ref.strain, 1e-12 * ref.strain);
  if (c.damping > 0)
  {
    EXPECT_LT(relative_difference(solver.dashpot_forces(), ref.Fd), 1e-12);
    EXPECT_LT(relative_difference(solver.dashpot_torques(), ref.Md), 1e-12);
    EXPECT_GT(relative_difference(ref.F, ref.Fd), 0.0); // the dashpots did act
  }
  // per bond, found by its particles (the solver reorders the bonds, a and b stay)
  std::vector<Vec3> got_F, want_F, got_M, want_M;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const auto& [F, M] = ref.bond.at({b.a[k], b.b[k]});
    got_F.push_back(b.force[k]), want_F.push_back(F);
    got_M.push_back(b.moment[k]), want_M.push_back(M);
  }
  EXPECT_LT(relative_difference(got_F, want_F), 1e-12);
  EXPECT_LT(relative_difference(got_M, want_M), 1e-12);
  // what the ParaView bond files show, evaluated per bond on demand (particle_stress.h): the
  // same law, dashpots included
  std::vector<Vec3> demand_F, demand_M;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const BondContactForce f = bond_contact_force(p, b, k);
    demand_F.push_back(f.force), demand_M.push_back(f.moment);
  }
  EXPECT_LT(relative_difference(demand_F, want_F), 1e-12);
  EXPECT_LT(relative_difference(demand_M, want_M), 1e-12);

  // One step on the hot path (no record): v^{n+1/2} - v^{n-1/2} = dt F / m with the scalar
  // kernel's F.
  ParticleStore p2 = m.particles;
  BondStore b2 = m.bonds;
  const double dt = 0.5 * m.critical.critical();
  ExplicitSolver stepper(p2, b2, {}, {}, {}, {dt, 0.0, c.threads});
  stepper.step(true);  // the first step records (initial energy)
  p2 = m.particles;    // back to the deformed state
  stepper.step(false); // the loop without records
  std::vector<Vec3> dv, want;
  for (std::size_t i = 0; i < p2.size(); ++i)
    dv.push_back(p2.velocity[i] - m.particles.velocity[i]),
        want.push_back((dt / m.particles.mass[i]) * ref.F[i]);
  EXPECT_LT(relative_difference(dv, want), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(LatticeAndRandom, BondLoop,
                         ::testing::Values(Case{ParticleSource::Kind::hcp, 0.05, 1},
                                           Case{ParticleSource::Kind::hcp, 0.0, 1},
                                           Case{ParticleSource::Kind::hcp, 0.05, 2},
                                           Case{ParticleSource::Kind::hcp, 0.0, 2},
                                           Case{ParticleSource::Kind::random, 0.05, 1},
                                           Case{ParticleSource::Kind::random, 0.0, 1},
                                           Case{ParticleSource::Kind::random, 0.05, 2},
                                           Case{ParticleSource::Kind::random, 0.0, 2}),
                         [](const auto& info)
                         {
                           const Case& c = info.param;
                           return std::string(c.kind == ParticleSource::Kind::hcp ? "hcp"
                                                                                  : "random") +
                                  (c.damping > 0 ? "_dashpots" : "_no_dashpots") + "_threads" +
                                  std::to_string(c.threads);
                         });
/// The records a block hands to the scatter (bond_block.h): which end gets what (end_lanes, by
/// a lane mask) against the law's resultants bond by bond, and the in-register transposes
/// (store_records) against one value at a time, bitwise, for both orders of a bond's ends, with
/// and without dashpots (a swapped lane, slot or choice of end fails it).
template <bool dashpots> void check_particle_records()
{
  constexpr int W = BondBlock::W, S = particle_record_size<dashpots>;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  BondForcesOf<Lanes> f;
  Lanes ma[3], mb[3], mda[3], mdb[3];
  for (Lanes* v : {f.Fc, f.Fd, ma, mb, mda, mdb})
    for (int d = 0; d < 3; ++d)
      for (int j = 0; j < W; ++j)
        v[d][j] = u(rng);
  f.Fc[1][2] = 0.0; // a signed zero must come out negated on one end
  LaneIndices ia, ib;
  for (int j = 0; j < W; ++j)
    ia[j] = 10 * j + (j % 3 == 0 ? 7 : 0), ib[j] = 10 * j + 3; // a < b in some lanes only
  const auto ends = end_lanes<dashpots>(ia, ib, f, ma, mb, mda, mdb);
  BondBlock lanes, scalar;
  store_records<S>(ends.lower, lanes.lower);
  store_records<S>(ends.upper, lanes.upper);
  store_records_scalar<S>(ends.lower, scalar.lower);
  store_records_scalar<S>(ends.upper, scalar.upper);
  for (int j = 0; j < W; ++j)
    for (int d = 0; d < S; ++d)
    {
      EXPECT_EQ(std::signbit(lanes.lower[j][d]), std::signbit(scalar.lower[j][d])) << j << d;
      EXPECT_EQ(lanes.lower[j][d], scalar.lower[j][d]) << "lane " << j << " slot " << d;
      EXPECT_EQ(lanes.upper[j][d], scalar.upper[j][d]) << "lane " << j << " slot " << d;
    }
  // what the law's resultants say (bond_kernel.h): -F_c and M_a on a, F_c and M_b on b
  for (int j = 0; j < W; ++j)
  {
    const bool a_lower = ia[j] < ib[j];
    const double* on_a = a_lower ? scalar.lower[j] : scalar.upper[j];
    const double* on_b = a_lower ? scalar.upper[j] : scalar.lower[j];
    for (int d = 0; d < 3; ++d)
    {
      EXPECT_EQ(on_a[d], -f.Fc[d][j]);
      EXPECT_EQ(on_b[d], f.Fc[d][j]);
      EXPECT_EQ(on_a[3 + d], ma[d][j]);
      EXPECT_EQ(on_b[3 + d], mb[d][j]);
      if (dashpots)
      {
        EXPECT_EQ(on_a[6 + d], -f.Fd[d][j]);
        EXPECT_EQ(on_b[6 + d], f.Fd[d][j]);
        EXPECT_EQ(on_a[9 + d], mda[d][j]);
        EXPECT_EQ(on_b[9 + d], mdb[d][j]);
      }
    }
    EXPECT_TRUE(std::signbit(on_a[1]) != std::signbit(on_b[1]) || j != 2);
  }
}

TEST(BondBlockRecords, LanesEqualOneBondAtATime)
{
  check_particle_records<true>();
  check_particle_records<false>();
}
} // namespace
