// The size estimate behind the memory guard (dem/model/size_estimate.h): the lattice counts are
// exact, the bond and random-packing counts upper bounds within stated margins, and the memory
// estimate stays above the heap a built model really holds (so that a field added to the stores
// without updating the estimate fails here), and the guard refuses with the figures.
#include "dem/model/model.h"
#include "dem/model/size_estimate.h"
#include "dem/packing/packings.h"
#include "dem/solvers/explicit_solver.h"
#include <gtest/gtest.h>
#include <malloc.h>

using namespace dembridge;
using namespace dembridge::dem;

namespace
{
CaseConfig specimen(ParticleSource::Kind kind, double r, Vec3 box = Vec3(0.25, 0.1, 0.1))
{
  CaseConfig c;
  c.particles.kind = kind;
  c.particles.radius = r;
  c.particles.box_size = box;
  c.bonds.material.model = BondModel::parallel_bond;
  c.bonds.material.youngs_modulus = 4e9;
  c.bonds.material.poisson_ratio = 0.3;
  return c;
}

/// Bytes the program holds from malloc: the arena's chunks in use and the blocks glibc maps
/// separately (every allocation above the mmap threshold, e.g. a store's vector).
double heap_in_use()
{
  const auto m = mallinfo2();
  return double(m.uordblks) + double(m.hblkhd);
}
} // namespace

// Lattice counts: exactly the spheres packings.cc lays, for the three lattices, radii that fill
// the box unevenly and boxes of odd shape.
TEST(SizeEstimate, LatticeCountsAreExact)
{
  using K = ParticleSource::Kind;
  for (K kind : {K::cubic, K::hcp, K::fcc})
    for (double r : {0.0125, 0.007, 0.005, 0.0031})
      for (Vec3 box : {Vec3(0.25, 0.1, 0.1), Vec3(0.031, 0.2, 0.057), Vec3(0.02, 0.02, 0.02)})
      {
        CaseConfig c = specimen(kind, r, box);
        ParticleStore p;
        if (box.minCoeff() < 2 * r)
        {
          // a box smaller than one sphere: the build refuses it, the estimate counts nothing
          EXPECT_THROW(generate_particles(c.particles, p), InputError);
          EXPECT_EQ(estimate_size(c).particles, 0.0);
          continue;
        }
        generate_particles(c.particles, p);
        EXPECT_EQ(estimate_size(c).particles, double(p.size()))
            << "kind " << int(kind) << ", r " << r << ", box " << box.transpose();
      }
}

// Bonds: the bulk coordination of the lattice (cubic 6, HCP and FCC 12; with a contact radius
// multiplier of 1.5 the cubic lattice's face diagonals join: 18) is an upper bound; the
// specimen's surface holds fewer, by at most 25 % for these specimens.
TEST(SizeEstimate, BondCountsBoundTheLattice)
{
  using K = ParticleSource::Kind;
  for (auto [kind, multiplier] : {std::pair{K::cubic, 1.0}, std::pair{K::hcp, 1.0},
                                  std::pair{K::fcc, 1.0}, std::pair{K::cubic, 1.5}})
  {
    CaseConfig c = specimen(kind, 0.005);
    c.bonds.contact_radius_multiplier = multiplier;
    const Model m = build_model(c);
    const double estimate = estimate_size(c).bonds;
    EXPECT_GE(estimate, double(m.bonds.size()));
    EXPECT_LE(estimate, 1.25 * double(m.bonds.size()));
  }
}

// A random packing: the packer draws (1 - target porosity) of the box (default target 0.37) and
// removes spheres if it jams short of full size. The thesis specimen (r = 5 mm) ends at porosity
// 0.397-0.399 (docs/specimens.md), so the drawn count bounds the final one within
// 0.63 / 0.601 = 1.048, i.e. 5 %. (Smaller specimens end more porous near the walls: at r = 7.5 mm
// 0.415 and 1.076.)
TEST(SizeEstimate, RandomPackingCountIsAnUpperBound)
{
  CaseConfig c = specimen(ParticleSource::Kind::random, 0.005);
  ParticleStore p;
  generate_particles(c.particles, p);
  const double estimate = estimate_size(c).particles;
  EXPECT_GE(estimate, double(p.size()));
  EXPECT_LE(estimate, 1.05 * double(p.size()));
}

// The estimate covers the heap a built model and its explicit solver hold (26,004 particles,
// 147,618 bonds at r = 2.5 mm), and is not wasteful: at most 4x (it also covers the output and
// the vectors' growth, which this does not measure).
TEST(SizeEstimate, MemoryCoversTheBuiltModel)
{
  const CaseConfig c = specimen(ParticleSource::Kind::hcp, 0.0025);
  const double before = heap_in_use();
  Model m = build_model(c);
  ExplicitSolver solver(m.particles, m.bonds, m.groups, m.constraints, m.loads,
                        {m.time_step, 0.0, 1});
  solver.step(true);
  const double used = heap_in_use() - before;
  if (!(used > 0))
    GTEST_SKIP() << "mallinfo2 reports no heap use (a sanitizer's allocator?)";
  const double estimate = estimate_size(c).bytes;
  std::printf("heap of the model and solver %.1f MB, estimate %.1f MB (%.2f x)\n", used / 1e6,
              estimate / 1e6, estimate / used);
  EXPECT_GE(estimate, used);
  EXPECT_LE(estimate, 4 * used);
}

// The guard: one line naming the key, the counts, the estimate and the available memory;
// nothing refused where the available memory is unknown (0).
TEST(SizeEstimate, GuardRefusesWithTheFigures)
{
  const CaseConfig c = specimen(ParticleSource::Kind::cubic, 1e-5);
  const SizeEstimate e = estimate_size(c);
  EXPECT_NEAR(e.particles, 12500.0 * 5000 * 5000, 1);
  EXPECT_NO_THROW(check_fits_in_memory(e, 0));
  try
  {
    check_fits_in_memory(e, 8e9);
    FAIL() << "not refused";
  }
  catch (const InputError& error)
  {
    const std::string what = error.what();
    EXPECT_EQ(what.rfind("Particles/radius: the case would make about 3.12e+11 particles", 0), 0u)
        << what;
    EXPECT_NE(what.find("this machine has 8 GB available"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  EXPECT_GT(available_memory_bytes(), 0.0); // Linux: /proc/meminfo
  EXPECT_EQ(human_bytes(2.46e15), "2.46 PB");
}
