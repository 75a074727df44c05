#pragma once
// The entries a rank holds of a PETSc vector as a plain array, for fused loops without a PETSc
// call per entry. For a ghosted vector the array is its local form: the owned entries first,
// then the ghosts in the order of the ghost IndexSet (relevant minus owned); for a plain vector
// the owned entries. Changes to a ghost entry stay local until a ghost update.
#include "fem/elastic_problem.h"

#include <petscvec.h>

namespace dembridge::fem
{
class LocalArray
{
public:
  explicit LocalArray(const LA::MPI::Vector& v) : vec(static_cast<const Vec&>(v))
  {
    VecGhostGetLocalForm(vec, &local);
    const PetscErrorCode ierr = VecGetArray(local ? local : vec, &values);
    AssertThrow(ierr == 0, dealii::ExcPETScError(ierr));
  }
  ~LocalArray()
  {
    VecRestoreArray(local ? local : vec, &values);
    if (local)
      VecGhostRestoreLocalForm(vec, &local);
  }
  LocalArray(const LocalArray&) = delete;
  LocalArray& operator=(const LocalArray&) = delete;
  double& operator[](const std::size_t i) { return values[i]; }
  double* data() { return values; }
  /// Owned plus ghost entries.
  std::size_t size() const
  {
    PetscInt n = 0;
    VecGetLocalSize(local ? local : vec, &n);
    return std::size_t(n);
  }

private:
  Vec vec, local = nullptr;
  PetscScalar* values = nullptr;
};

/// Adds the ghost entries of @p v's local form to their owners' entries (collective).
inline void add_ghosts_to_owners(LA::MPI::Vector& v)
{
  const Vec x = static_cast<const Vec&>(v);
  VecGhostUpdateBegin(x, ADD_VALUES, SCATTER_REVERSE);
  VecGhostUpdateEnd(x, ADD_VALUES, SCATTER_REVERSE);
}
} // namespace dembridge::fem
