#pragma once
// Algebraic multigrid for the quasi-static bond network (dem/solvers/static_solver.h): PETSc's
// smoothed-aggregation AMG (GAMG; Adams, Bayraktar, Keyes & Tang, "Parallel multigrid smoothing:
// polynomial versus Gauss-Seidel", J. Comput. Phys. 188, 2003; PETSc manual, PCGAMG) as the
// preconditioner of conjugate gradients on the Jacobi-scaled stiffness A = S K_ff S.
//
// Smoothed aggregation builds its coarse spaces from a near-null space: the motions that cost
// (almost) no energy away from the supports. For a network of particles with 6 DOFs each
// [u, theta] these are the six rigid-body modes
//   translation e_k:   u_i = e_k,                  theta_i = 0
//   rotation about e_k: u_i = e_k x (x_i - x_c),    theta_i = e_k        (k = 1, 2, 3)
// (x_c: the centroid, for conditioning), which every bond's stiffness annihilates (bond_matrix.h),
// taken into the scaled unknowns (y = S^-1 u) and orthonormalised. The matrix is handed to PETSc
// over all 6 DOFs of every particle (held DOFs as identity rows) with block size 6, so that
// aggregates hold whole particles. Jacobi CG needs O(h^-1) iterations (about 1,000 at 25 k
// particles); with this space the iteration count stays nearly flat as the network grows.
//
// PETSc must be initialised (deal.II's Utilities::MPI::MPI_InitFinalize does it). The solve is
// serial (MPI_COMM_SELF) or shared by the ranks of GamgSettings::communicator: every rank holds
// the same system (the assembly is replicated) and inserts only its own rows of a parallel AIJ
// matrix, whole particles in contiguous ranges; CG and GAMG run on the ranks together and every
// rank gets the whole solution back.
#include "dem/solvers/static_solver.h"
#include <functional>
#include <mpi.h>

namespace dembridge::fem
{
struct GamgSettings
{
  /// Aggregation graph drop tolerance (PCGAMGSetThreshold): couplings weaker than this, relative
  /// to the diagonal, are left out of the aggregation graph.
  double threshold = 0.01;
  long max_iterations = 20000;
  /// The ranks that share the solve; each calls it with the same system. MPI_COMM_SELF: serial.
  MPI_Comm communicator = MPI_COMM_SELF;
  /// false: CG without a preconditioner beyond the Jacobi scaling the system already has (the
  /// Jacobi CG of static_solver.h, on the communicator's ranks).
  bool multigrid = true;
};

/// Solves the static solver's scaled system by PETSc CG preconditioned with GAMG, to
/// |b - A y| <= tolerance |b| (the true residual, as Eigen's CG measures it). On several ranks
/// the method names them and the matrix's rows each holds, e.g. "PETSc CG+GAMG on 2 ranks
/// (mpiaij rows 9612 + 9612)".
dem::StaticLinearSolution solve_bond_network_gamg(const dem::StaticLinearSystem& system,
                                                  const GamgSettings& settings = {});

/// solve_bond_network_gamg as a dem::StaticSettings::iterative_solver.
std::function<dem::StaticLinearSolution(const dem::StaticLinearSystem&)>
gamg_iterative_solver(const GamgSettings& settings = {});
} // namespace dembridge::fem
