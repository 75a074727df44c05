// PETSc CG + GAMG for the static solver's scaled system; the method is in bond_network_solver.h.
#include "fem/bond_network_solver.h"
#include <chrono>
#include <memory>
#include <petscksp.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace dembridge::fem
{
namespace
{
void check(PetscErrorCode ierr, const char* what)
{
  if (ierr != 0)
    throw std::runtime_error(std::string("static solver (GAMG): PETSc error ") +
                             std::to_string(int(ierr)) + " in " + what);
}

/// Owns PETSc objects for the length of one solve.
struct PetscObjects
{
  Mat A = nullptr;
  Vec b = nullptr, x = nullptr;
  Vec modes[6] = {};
  MatNullSpace near_null = nullptr;
  KSP ksp = nullptr;
  ~PetscObjects()
  {
    if (ksp)
      KSPDestroy(&ksp);
    if (near_null)
      MatNullSpaceDestroy(&near_null);
    for (Vec& v : modes)
      if (v)
        VecDestroy(&v);
    if (x)
      VecDestroy(&x);
    if (b)
      VecDestroy(&b);
    if (A)
      MatDestroy(&A);
  }
};
} // namespace

dem::StaticLinearSolution solve_bond_network_gamg(const dem::StaticLinearSystem& s,
                                                  const GamgSettings& settings)
{
  using clock = std::chrono::steady_clock;
  PetscBool initialised = PETSC_FALSE;
  PetscInitialized(&initialised);
  if (!initialised)
    throw std::runtime_error("static solver (GAMG): PETSc is not initialised (construct "
                             "dealii::Utilities::MPI::MPI_InitFinalize first)");
  const Eigen::SparseMatrix<double>& L = s.matrix; // lower triangle of A, column-major
  const std::vector<int>& index = s.free_index;
  const PetscInt n_all = PetscInt(index.size()); // 6 per particle
  const long n_free = L.cols();
  std::vector<PetscInt> dof_of(std::size_t(n_free), 0); // free unknown -> particle DOF
  for (PetscInt g = 0; g < n_all; ++g)
    if (index[std::size_t(g)] >= 0)
      dof_of[std::size_t(index[std::size_t(g)])] = g;

  PetscObjects o;
  // A over all particle DOFs: the free block, identity rows and columns on held DOFs.
  // Preallocation: row nonzeros of the full symmetric matrix from its lower triangle.
  std::vector<PetscInt> row_nnz(std::size_t(n_all), 1); // held DOFs: the unit diagonal
  for (long c = 0; c < n_free; ++c)
    row_nnz[std::size_t(dof_of[std::size_t(c)])] = 0;
  for (long c = 0; c < n_free; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, c); it; ++it)
    {
      ++row_nnz[std::size_t(dof_of[std::size_t(it.row())])];
      if (it.row() != c)
        ++row_nnz[std::size_t(dof_of[std::size_t(c)])];
    }
  check(MatCreate(PETSC_COMM_SELF, &o.A), "MatCreate");
  check(MatSetSizes(o.A, n_all, n_all, n_all, n_all), "MatSetSizes");
  check(MatSetType(o.A, MATSEQAIJ), "MatSetType");
  check(MatSetBlockSize(o.A, 6), "MatSetBlockSize"); // aggregates of whole particles
  check(MatSeqAIJSetPreallocation(o.A, 0, row_nnz.data()), "MatSeqAIJSetPreallocation");
  std::vector<PetscInt>().swap(row_nnz);
  // Column c of the lower triangle gives row c's entries right of the diagonal and, one at a
  // time, column c's entries below it; every row then receives its columns in ascending order.
  std::vector<PetscInt> rows;
  std::vector<PetscScalar> values;
  const PetscScalar one = 1;
  for (PetscInt g = 0; g < n_all; ++g)
    if (index[std::size_t(g)] < 0)
      check(MatSetValues(o.A, 1, &g, 1, &g, &one, INSERT_VALUES), "MatSetValues");
  for (long c = 0; c < n_free; ++c)
  {
    const PetscInt gc = dof_of[std::size_t(c)];
    rows.clear();
    values.clear();
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, c); it; ++it)
    {
      rows.push_back(dof_of[std::size_t(it.row())]);
      values.push_back(it.value());
    }
    check(
        MatSetValues(o.A, PetscInt(rows.size()), rows.data(), 1, &gc, values.data(), INSERT_VALUES),
        "MatSetValues");
    // the row part right of the diagonal (the column's first entry is its diagonal)
    if (rows.empty() || rows.front() != gc)
      throw std::logic_error("static solver (GAMG): a column of A without its diagonal");
    if (rows.size() > 1)
      check(MatSetValues(o.A, 1, &gc, PetscInt(rows.size()) - 1, rows.data() + 1, values.data() + 1,
                         INSERT_VALUES),
            "MatSetValues");
  }
  check(MatAssemblyBegin(o.A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(o.A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");

  // Right-hand side, zero on held DOFs.
  check(MatCreateVecs(o.A, &o.x, &o.b), "MatCreateVecs");
  {
    PetscScalar* bb = nullptr;
    check(VecGetArray(o.b, &bb), "VecGetArray");
    for (PetscInt g = 0; g < n_all; ++g)
      bb[g] = index[std::size_t(g)] >= 0 ? s.rhs[index[std::size_t(g)]] : 0.0;
    check(VecRestoreArray(o.b, &bb), "VecRestoreArray");
  }

  // Near-null space: the six rigid-body modes in the scaled unknowns, orthonormalised.
  const std::size_t n_particles = index.size() / 6;
  dem::Vec3 centre = dem::Vec3::Zero();
  for (std::size_t i = 0; i < n_particles; ++i)
    centre += s.positions[i];
  centre /= double(std::max<std::size_t>(n_particles, 1));
  for (int m = 0; m < 6; ++m)
  {
    check(VecDuplicate(o.b, &o.modes[m]), "VecDuplicate");
    PetscScalar* v = nullptr;
    check(VecGetArray(o.modes[m], &v), "VecGetArray");
    for (std::size_t i = 0; i < n_particles; ++i)
    {
      Eigen::Matrix<double, 6, 1> u = Eigen::Matrix<double, 6, 1>::Zero();
      if (m < 3)
        u[m] = 1;
      else
      {
        const dem::Vec3 axis = dem::Vec3::Unit(m - 3);
        u.head<3>() = axis.cross(s.positions[i] - centre);
        u[m] = 1;
      }
      for (int k = 0; k < 6; ++k)
      {
        const int r = index[6 * i + std::size_t(k)];
        v[6 * i + std::size_t(k)] = r >= 0 ? u[k] / s.scale[r] : 0.0; // y = S^-1 u
      }
    }
    check(VecRestoreArray(o.modes[m], &v), "VecRestoreArray");
    // modified Gram-Schmidt against the modes before it
    for (int q = 0; q < m; ++q)
    {
      PetscScalar dot = 0;
      check(VecDot(o.modes[m], o.modes[q], &dot), "VecDot");
      check(VecAXPY(o.modes[m], -dot, o.modes[q]), "VecAXPY");
    }
    PetscReal norm = 0;
    check(VecNormalize(o.modes[m], &norm), "VecNormalize");
    if (!(norm > 0))
      throw std::runtime_error("static solver (GAMG): a rigid-body mode vanishes on the free "
                               "DOFs (every particle held?)");
  }
  check(MatNullSpaceCreate(PETSC_COMM_SELF, PETSC_FALSE, 6, o.modes, &o.near_null),
        "MatNullSpaceCreate");
  check(MatSetNearNullSpace(o.A, o.near_null), "MatSetNearNullSpace");

  // CG on the true residual (as Eigen's CG), GAMG preconditioner.
  check(KSPCreate(PETSC_COMM_SELF, &o.ksp), "KSPCreate");
  check(KSPSetOperators(o.ksp, o.A, o.A), "KSPSetOperators");
  check(KSPSetType(o.ksp, KSPCG), "KSPSetType");
  check(KSPSetNormType(o.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  check(KSPSetTolerances(o.ksp, s.tolerance, 0.0, PETSC_DEFAULT, PetscInt(settings.max_iterations)),
        "KSPSetTolerances");
  PC pc = nullptr;
  check(KSPGetPC(o.ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  PetscReal threshold = settings.threshold;
  check(PCGAMGSetThreshold(pc, &threshold, 1), "PCGAMGSetThreshold");
  // why: PETSc's options (PETSC_OPTIONS, e.g. -pc_gamg_threshold, -ksp_view) still apply
  check(KSPSetFromOptions(o.ksp), "KSPSetFromOptions");
  const auto t0 = clock::now();
  check(KSPSetUp(o.ksp), "KSPSetUp");
  check(PCSetUp(pc), "PCSetUp"); // the multigrid hierarchy, timed as set-up
  const auto t1 = clock::now();
  check(KSPSolve(o.ksp, o.b, o.x), "KSPSolve");

  dem::StaticLinearSolution out;
  out.method = "PETSc CG+GAMG";
  out.setup_seconds = std::chrono::duration<double>(t1 - t0).count();
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(o.ksp, &iterations), "KSPGetIterationNumber");
  out.iterations = long(iterations);
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(o.ksp, &reason), "KSPGetConvergedReason");
  out.converged = reason > 0;
  out.y.resize(n_free);
  const PetscScalar* xx = nullptr;
  check(VecGetArrayRead(o.x, &xx), "VecGetArrayRead");
  for (long r = 0; r < n_free; ++r)
    out.y[r] = xx[dof_of[std::size_t(r)]];
  check(VecRestoreArrayRead(o.x, &xx), "VecRestoreArrayRead");
  return out;
}

std::function<dem::StaticLinearSolution(const dem::StaticLinearSystem&)>
gamg_iterative_solver(const GamgSettings& settings)
{
  return [settings](const dem::StaticLinearSystem& s)
  { return solve_bond_network_gamg(s, settings); };
}
} // namespace dembridge::fem
