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
  Vec b = nullptr, x = nullptr, x_all = nullptr;
  VecScatter to_all = nullptr;
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
    if (to_all)
      VecScatterDestroy(&to_all);
    if (x_all)
      VecDestroy(&x_all);
    if (x)
      VecDestroy(&x);
    if (b)
      VecDestroy(&b);
    if (A)
      MatDestroy(&A);
  }
};

/// The rows [first, last) of the particle DOFs that this rank holds: whole particles, in
/// contiguous ranges of nearly equal particle counts.
struct OwnedRows
{
  PetscInt first = 0, last = 0;
  bool holds(PetscInt g) const { return g >= first && g < last; }
};

OwnedRows owned_rows(std::size_t n_particles, MPI_Comm comm)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const auto begin = [&](int r) { return PetscInt(6 * (n_particles * std::size_t(r) / size)); };
  return {begin(rank), begin(rank + 1)};
}

/// A over all particle DOFs (the free block; identity rows and columns on held DOFs), this
/// rank's rows only. Column c of the lower triangle L gives row c's entries right of the diagonal
/// and, one at a time, column c's entries below it.
void assemble_matrix(PetscObjects& o, const dem::StaticLinearSystem& s,
                     const std::vector<PetscInt>& dof_of, const OwnedRows& own, MPI_Comm comm)
{
  const Eigen::SparseMatrix<double>& L = s.matrix;
  const std::vector<int>& index = s.free_index;
  const PetscInt n_all = PetscInt(index.size());
  const long n_free = L.cols();
  const PetscInt n_own = own.last - own.first;
  // preallocation: each owned row's nonzeros in the owned columns (d) and the others (o)
  std::vector<PetscInt> d_nnz(std::size_t(n_own), 0), o_nnz(std::size_t(n_own), 0);
  const auto count = [&](PetscInt row, PetscInt col)
  {
    if (own.holds(row))
      ++(own.holds(col) ? d_nnz : o_nnz)[std::size_t(row - own.first)];
  };
  for (PetscInt g = own.first; g < own.last; ++g)
    if (index[std::size_t(g)] < 0)
      count(g, g); // held DOF: the unit diagonal
  for (long c = 0; c < n_free; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, c); it; ++it)
    {
      const PetscInt gr = dof_of[std::size_t(it.row())], gc = dof_of[std::size_t(c)];
      count(gr, gc);
      if (gr != gc)
        count(gc, gr);
    }
  check(MatCreate(comm, &o.A), "MatCreate");
  check(MatSetSizes(o.A, n_own, n_own, n_all, n_all), "MatSetSizes");
  check(MatSetType(o.A, MATAIJ), "MatSetType");      // seqaij on one rank, mpiaij on several
  check(MatSetBlockSize(o.A, 6), "MatSetBlockSize"); // aggregates of whole particles
  check(MatSeqAIJSetPreallocation(o.A, 0, d_nnz.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(o.A, 0, d_nnz.data(), 0, o_nnz.data()),
        "MatMPIAIJSetPreallocation");
  // why: every rank inserts its own rows only; an entry for another rank would be a bug here
  check(MatSetOption(o.A, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE), "MatSetOption");
  const PetscScalar one = 1;
  for (PetscInt g = own.first; g < own.last; ++g)
    if (index[std::size_t(g)] < 0)
      check(MatSetValues(o.A, 1, &g, 1, &g, &one, INSERT_VALUES), "MatSetValues");
  std::vector<PetscInt> rows, own_rows;
  std::vector<PetscScalar> values, own_values;
  for (long c = 0; c < n_free; ++c)
  {
    const PetscInt gc = dof_of[std::size_t(c)];
    rows.clear(), values.clear(), own_rows.clear(), own_values.clear();
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, c); it; ++it)
    {
      const PetscInt gr = dof_of[std::size_t(it.row())];
      rows.push_back(gr);
      values.push_back(it.value());
      if (own.holds(gr))
        own_rows.push_back(gr), own_values.push_back(it.value());
    }
    if (rows.empty() || rows.front() != gc) // the column's first entry is its diagonal
      throw std::logic_error("static solver (GAMG): a column of A without its diagonal");
    if (!own_rows.empty())
      check(MatSetValues(o.A, PetscInt(own_rows.size()), own_rows.data(), 1, &gc, own_values.data(),
                         INSERT_VALUES),
            "MatSetValues");
    if (own.holds(gc) && rows.size() > 1) // the row part right of the diagonal
      check(MatSetValues(o.A, 1, &gc, PetscInt(rows.size()) - 1, rows.data() + 1, values.data() + 1,
                         INSERT_VALUES),
            "MatSetValues");
  }
  check(MatAssemblyBegin(o.A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(o.A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

/// The six rigid-body modes in the scaled unknowns, this rank's entries, orthonormalised.
void set_near_null_space(PetscObjects& o, const dem::StaticLinearSystem& s, const OwnedRows& own,
                         MPI_Comm comm)
{
  const std::vector<int>& index = s.free_index;
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
    for (std::size_t i = std::size_t(own.first / 6); i < std::size_t(own.last / 6); ++i)
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
      for (std::size_t k = 0; k < 6; ++k)
      {
        const int r = index[6 * i + k];
        v[6 * i + k - std::size_t(own.first)] = r >= 0 ? u[k] / s.scale[r] : 0.0; // y = S^-1 u
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
  check(MatNullSpaceCreate(comm, PETSC_FALSE, 6, o.modes, &o.near_null), "MatNullSpaceCreate");
  check(MatSetNearNullSpace(o.A, o.near_null), "MatSetNearNullSpace");
}

/// "PETSc CG+GAMG", and on several ranks "... on N ranks (mpiaij rows n_0 + n_1 + ...)" with the
/// rows PETSc holds on each rank.
std::string method_name(const PetscObjects& o, bool multigrid, MPI_Comm comm)
{
  std::string name = multigrid ? "PETSc CG+GAMG" : "PETSc CG+Jacobi";
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size == 1)
    return name;
  PetscInt first = 0, last = 0;
  check(MatGetOwnershipRange(o.A, &first, &last), "MatGetOwnershipRange");
  long local = long(last - first);
  std::vector<long> rows(std::size_t(size), 0);
  MPI_Allgather(&local, 1, MPI_LONG, rows.data(), 1, MPI_LONG, comm);
  MatType type = nullptr;
  check(MatGetType(o.A, &type), "MatGetType");
  name += " on " + std::to_string(size) + " ranks (" + type + " rows";
  for (std::size_t r = 0; r < rows.size(); ++r)
    name += (r ? " + " : " ") + std::to_string(rows[r]);
  return name + ")";
}
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
  const MPI_Comm comm = settings.communicator;
  const std::vector<int>& index = s.free_index;
  const PetscInt n_all = PetscInt(index.size()); // 6 per particle
  const long n_free = s.matrix.cols();
  std::vector<PetscInt> dof_of(std::size_t(n_free), 0); // free unknown -> particle DOF
  for (PetscInt g = 0; g < n_all; ++g)
    if (index[std::size_t(g)] >= 0)
      dof_of[std::size_t(index[std::size_t(g)])] = g;
  const OwnedRows own = owned_rows(index.size() / 6, comm);

  PetscObjects o;
  assemble_matrix(o, s, dof_of, own, comm);
  // right-hand side, zero on held DOFs
  check(MatCreateVecs(o.A, &o.x, &o.b), "MatCreateVecs");
  {
    PetscScalar* bb = nullptr;
    check(VecGetArray(o.b, &bb), "VecGetArray");
    for (PetscInt g = own.first; g < own.last; ++g)
      bb[g - own.first] = index[std::size_t(g)] >= 0 ? s.rhs[index[std::size_t(g)]] : 0.0;
    check(VecRestoreArray(o.b, &bb), "VecRestoreArray");
  }
  if (settings.multigrid)
    set_near_null_space(o, s, own, comm);

  // CG on the true residual (as Eigen's CG), GAMG preconditioner
  check(KSPCreate(comm, &o.ksp), "KSPCreate");
  check(KSPSetOperators(o.ksp, o.A, o.A), "KSPSetOperators");
  check(KSPSetType(o.ksp, KSPCG), "KSPSetType");
  check(KSPSetNormType(o.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  check(KSPSetTolerances(o.ksp, s.tolerance, 0.0, PETSC_DEFAULT, PetscInt(settings.max_iterations)),
        "KSPSetTolerances");
  PC pc = nullptr;
  check(KSPGetPC(o.ksp, &pc), "KSPGetPC");
  if (settings.multigrid)
  {
    check(PCSetType(pc, PCGAMG), "PCSetType");
    PetscReal threshold = settings.threshold;
    check(PCGAMGSetThreshold(pc, &threshold, 1), "PCGAMGSetThreshold");
  }
  else // the system is Jacobi-scaled already (unit diagonal)
    check(PCSetType(pc, PCNONE), "PCSetType");
  // why: PETSc's options (PETSC_OPTIONS, e.g. -pc_gamg_threshold, -ksp_view) still apply
  check(KSPSetFromOptions(o.ksp), "KSPSetFromOptions");
  const auto t0 = clock::now();
  check(KSPSetUp(o.ksp), "KSPSetUp");
  check(PCSetUp(pc), "PCSetUp"); // the multigrid hierarchy, timed as set-up
  const auto t1 = clock::now();
  check(KSPSolve(o.ksp, o.b, o.x), "KSPSolve");

  dem::StaticLinearSolution out;
  out.method = method_name(o, settings.multigrid, comm);
  out.setup_seconds = std::chrono::duration<double>(t1 - t0).count();
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(o.ksp, &iterations), "KSPGetIterationNumber");
  out.iterations = long(iterations);
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(o.ksp, &reason), "KSPGetConvergedReason");
  out.converged = reason > 0;
  // every rank gets the whole solution (the model and its measurements are replicated)
  check(VecScatterCreateToAll(o.x, &o.to_all, &o.x_all), "VecScatterCreateToAll");
  check(VecScatterBegin(o.to_all, o.x, o.x_all, INSERT_VALUES, SCATTER_FORWARD), "VecScatter");
  check(VecScatterEnd(o.to_all, o.x, o.x_all, INSERT_VALUES, SCATTER_FORWARD), "VecScatter");
  out.y.resize(n_free);
  const PetscScalar* xx = nullptr;
  check(VecGetArrayRead(o.x_all, &xx), "VecGetArrayRead");
  for (long r = 0; r < n_free; ++r)
    out.y[r] = xx[dof_of[std::size_t(r)]];
  check(VecRestoreArrayRead(o.x_all, &xx), "VecRestoreArrayRead");
  return out;
}

std::function<dem::StaticLinearSolution(const dem::StaticLinearSystem&)>
gamg_iterative_solver(const GamgSettings& settings)
{
  return [settings](const dem::StaticLinearSystem& s)
  { return solve_bond_network_gamg(s, settings); };
}
} // namespace dembridge::fem
