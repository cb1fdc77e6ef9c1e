// Bringing distributed values to rank 0 (sensors, results, checkpoints): one
// forward scatter into a vector whose local part is the gathered values on
// rank 0 and empty elsewhere, copied out into a std::vector.
#pragma once

#include <petscvec.h>

#include <vector>

namespace boomdyn {

// out = the local entries of dst after scattering src into it with sc
// (all of them on rank 0 for a scatter to rank 0, none on the others).
inline PetscErrorCode scatterValues(VecScatter sc, Vec src, Vec dst, std::vector<double> &out)
{
  const PetscScalar *a;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(sc, src, dst, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, src, dst, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetLocalSize(dst, &n));
  PetscCall(VecGetArrayRead(dst, &a));
  out.assign(a, a + n);
  PetscCall(VecRestoreArrayRead(dst, &a));
  PetscFunctionReturn(0);
}

// All of v on rank 0 (empty elsewhere), through a scatter made for this call.
inline PetscErrorCode gatherToZero(Vec v, std::vector<double> &out)
{
  VecScatter sc;
  Vec all;
  PetscFunctionBeginUser;
  PetscCall(VecScatterCreateToZero(v, &sc, &all));
  PetscCall(scatterValues(sc, v, all, out));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
