#pragma once
// How big a coupled run's continuum mesh will be before it is built (the memory guard): the
// graded box of coupled_mesh.h, counted from its cell sizes along each axis, with the
// particle-only cells left in (an upper bound: they are cut out after the box is built).
#include "coupling/coupled_case.h"

namespace dembridge::coupling
{
struct ContinuumMeshSize
{
  double cells = 0; ///< of the graded box
  double dofs = 0;  ///< 3 per vertex of the box
};

/// The continuum of @p c as make_coupled_problem builds it (FE domain box, particle region,
/// band, Coupling/element sizes); throws std::runtime_error for a geometry the run would refuse.
ContinuumMeshSize estimate_continuum_mesh(const CoupledCase& c);
} // namespace dembridge::coupling
