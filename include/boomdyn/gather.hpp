// Bringing distributed values to rank 0 (sensors, results, checkpoints, mode
// shapes): one forward scatter into a vector whose local part is the gathered values on
// rank 0 and empty elsewhere, copied out into a std::vector.
#pragma once

#include "boomdyn/petsc_handle.hpp"

#include <petscvec.h>

#include <algorithm>
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

// Gathers to rank 0 through one scatter kept between calls: creating a
// scatter to zero (and its PetscSF, set up at the first use) cost more than
// the whole rest of gatherShape() at every tracking analysis. The scatter
// is remade when a vector of another layout or communicator comes (compared with
// PetscLayoutCompare, which reads the layout's range array, the same on
// every rank: all ranks decide alike, as the collective creation needs).
// On one rank nothing is scattered: the local array is all of v.
class ZeroGather {
public:
  ZeroGather() = default;
  ZeroGather(const ZeroGather &) = delete;
  ZeroGather &operator=(const ZeroGather &) = delete;
  ~ZeroGather() { (void)PetscLayoutDestroy(&layout_); }

  // out = the first `count` entries of v (all of them for count < 0) on
  // rank 0, empty elsewhere. Collective.
  PetscErrorCode gather(Vec v, std::vector<double> &out, PetscInt count = -1)
  {
    PetscMPIInt size, rank;
    PetscLayout layout;
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)v), &size));
    PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)v), &rank));
    Vec local = v;
    if (size > 1) {
      PetscBool same = PETSC_FALSE;
      PetscCall(VecGetLayout(v, &layout));
      if (layout_ && PetscObjectComm((PetscObject)v) == comm_) PetscCall(PetscLayoutCompare(layout_, layout, &same));
      if (!same) {
        PetscCall(VecScatterCreateToZero(v, scatter_.address(), gathered_.address()));
        PetscCall(PetscLayoutReference(layout, &layout_)); // keeps it alive for the comparison
        comm_ = PetscObjectComm((PetscObject)v);
      }
      PetscCall(VecScatterBegin(scatter_, v, gathered_, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterEnd(scatter_, v, gathered_, INSERT_VALUES, SCATTER_FORWARD));
      local = gathered_;
    }
    if (rank == 0) {
      const PetscScalar *a;
      PetscInt n;
      PetscCall(VecGetLocalSize(local, &n));
      if (count >= 0) n = std::min(n, count);
      PetscCall(VecGetArrayRead(local, &a));
      out.assign(a, a + n);
      PetscCall(VecRestoreArrayRead(local, &a));
    } else {
      out.clear();
    }
    PetscFunctionReturn(0);
  }

private:
  PetscLayout layout_ = nullptr; // the layout the scatter was made for (a reference)
  MPI_Comm comm_ = MPI_COMM_NULL; // and the communicator of its vectors
  PetscHandle<VecScatter> scatter_;
  PetscHandle<Vec> gathered_;
};

// All of v on rank 0 (empty elsewhere), through a scatter made for this call.
inline PetscErrorCode gatherToZero(Vec v, std::vector<double> &out)
{
  ZeroGather once;
  PetscFunctionBeginUser;
  PetscCall(once.gather(v, out));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
