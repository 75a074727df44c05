// The quasi-static solver with PETSc's GAMG (fem/bond_network_solver.h) against the Jacobi CG of
// dem/solvers/static_solver.cc on the thesis specimen in its compression test (compression_case.h):
//  - the same apparent modulus E = (F / A) / (delta / L) to 1e-6 and the same displacement field
//    to 1e-6 of its largest value, on an HCP lattice and on a random close packing;
//  - an iteration count nearly flat in the particle count: at 4x the particles GAMG needs less
//    than 2x the iterations (what an h-independent multigrid preconditioner gives; Jacobi CG's
//    count grows as 1/h, 4^(1/3) = 1.6x here, and is printed beside it).
#include "compression_case.h"
#include "dem/solvers/static_solver.h"
#include "fem/bond_network_solver.h"
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>
#include <iostream>

using namespace dembridge;
using namespace dembridge::dem;
using namespace dembridge::test;

namespace
{
struct Solved
{
  double modulus = 0; ///< Pa
  std::vector<Vec3> displacement;
  StaticResult result;
};

Solved solve(const Model& model, bool gamg)
{
  Model m = model;
  StaticSettings s;
  s.method = StaticSettings::Method::cg_jacobi;
  s.cg_tolerance = 1e-12;
  if (gamg)
    s.iterative_solver = fem::gamg_iterative_solver();
  Solved out;
  out.result = solve_static(m, s);
  out.modulus = compression_modulus(m);
  for (std::size_t i = 0; i < m.particles.size(); ++i)
    out.displacement.push_back(m.particles.position[i] - m.particles.reference_position[i]);
  std::cout << m.particles.size() << " particles, " << out.result.n_free_dofs
            << " unknowns: " << out.result.method << ", " << out.result.iterations
            << " iterations, " << out.result.solve_seconds << " s (set-up "
            << out.result.setup_seconds << " s), residual " << out.result.residual
            << ", E = " << out.modulus << " Pa\n";
  return out;
}

class SameModulus : public ::testing::TestWithParam<ParticleSource::Kind>
{
};

TEST_P(SameModulus, GamgGivesJacobiCgModulusToOneInAMillion)
{
  const Model model = build_model(compression_case(GetParam(), 5e-3));
  const Solved cg = solve(model, false), mg = solve(model, true);
  EXPECT_EQ(cg.result.method, "ConjugateGradient+Jacobi");
  EXPECT_EQ(mg.result.method, "PETSc CG+GAMG");
  EXPECT_LT(mg.result.residual, 1e-10);
  EXPECT_GT(cg.modulus, 0);
  EXPECT_NEAR(mg.modulus / cg.modulus, 1.0, 1e-6);
  double umax = 0, diff = 0;
  for (std::size_t i = 0; i < cg.displacement.size(); ++i)
  {
    umax = std::max(umax, cg.displacement[i].norm());
    diff = std::max(diff, (cg.displacement[i] - mg.displacement[i]).norm());
  }
  EXPECT_LT(diff, 1e-6 * umax);
}
INSTANTIATE_TEST_SUITE_P(Specimens, SameModulus,
                         ::testing::Values(ParticleSource::Kind::hcp, ParticleSource::Kind::random),
                         [](const auto& info)
                         { return info.param == ParticleSource::Kind::hcp ? "hcp" : "random"; });

// r = 5 mm and r = 5 mm / 4^(1/3): four times the particles of the same specimen.
TEST(GamgIterations, NearlyFlatInTheParticleCount)
{
  const Model small = build_model(compression_case(ParticleSource::Kind::hcp, 5e-3));
  const Model large =
      build_model(compression_case(ParticleSource::Kind::hcp, 5e-3 / std::cbrt(4.0)));
  const double ratio = double(large.particles.size()) / double(small.particles.size());
  ASSERT_GT(ratio, 3.5);
  ASSERT_LT(ratio, 4.5);
  const Solved mg_small = solve(small, true), mg_large = solve(large, true);
  const Solved cg_small = solve(small, false), cg_large = solve(large, false);
  std::cout << "particles x" << ratio << ": GAMG iterations x"
            << double(mg_large.result.iterations) / double(mg_small.result.iterations)
            << ", Jacobi CG iterations x"
            << double(cg_large.result.iterations) / double(cg_small.result.iterations) << "\n";
  EXPECT_GT(mg_small.result.iterations, 0);
  EXPECT_LT(mg_large.result.iterations, 2 * mg_small.result.iterations);
  EXPECT_NEAR(mg_large.modulus / cg_large.modulus, 1.0, 1e-6);
}
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1); // initialises PETSc
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
