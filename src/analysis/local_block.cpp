#include "boomdyn/local_block.hpp"

#include <algorithm>

namespace boomdyn {

PetscErrorCode LocalBlocks::setUp(Vec layout)
{
  PetscInt hi;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)layout, &comm_));
  PetscCallMPI(MPI_Comm_size(comm_, &size_));
  PetscCall(VecGetOwnershipRange(layout, &lo_, &hi));
  n_ = hi - lo_;
  PetscCall(VecDuplicate(layout, x_.address()));
  PetscCall(VecDuplicate(layout, y_.address()));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::inner(const Eigen::Ref<const Eigen::MatrixXd> &A,
                                  const Eigen::Ref<const Eigen::MatrixXd> &B, Eigen::MatrixXd *G) const
{
  PetscFunctionBeginUser;
  G->noalias() = A.transpose() * B;
  if (size_ > 1)
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, G->data(), (PetscMPIInt)G->size(), MPI_DOUBLE, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::columnNorms(const Eigen::Ref<const Eigen::MatrixXd> &A, Eigen::VectorXd *norms) const
{
  PetscFunctionBeginUser;
  *norms = A.colwise().squaredNorm().transpose();
  if (size_ > 1)
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, norms->data(), (PetscMPIInt)norms->size(), MPI_DOUBLE, MPI_SUM, comm_));
  *norms = norms->cwiseSqrt();
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::multiply(Mat M, const double *x, double *y)
{
  PetscFunctionBeginUser;
  // PETSc only reads the input of MatMult; VecPlaceArray takes a non-const pointer.
  PetscCall(VecPlaceArray(x_, const_cast<double *>(x)));
  PetscCall(VecPlaceArray(y_, y));
  PetscCall(MatMult(M, x_, y_));
  PetscCall(VecResetArray(x_));
  PetscCall(VecResetArray(y_));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::solve(KSP ksp, const double *b, double *x, bool *ok)
{
  KSPConvergedReason reason;
  PC pc;
  PetscBool preonly, lu;
  PetscFunctionBeginUser;
  PetscCall(VecPlaceArray(x_, const_cast<double *>(b)));
  PetscCall(VecPlaceArray(y_, x));
  // The shift-and-invert solvers are a factorization applied once
  // (useDirectSolver): the triangular solves directly, without KSPSolve's
  // overhead (a third of a solve at 221 unknowns). Anything else set from
  // the options goes through KSPSolve.
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  if (preonly && lu) {
    Mat factor;
    PCFailedReason failed;
    PetscCall(PCGetFailedReason(pc, &failed));
    *ok = failed == PC_NOERROR;
    PetscCall(PCFactorGetMatrix(pc, &factor));
    if (*ok) PetscCall(MatSolve(factor, x_, y_));
  } else {
    PetscCall(KSPSolve(ksp, x_, y_));
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    *ok = reason >= 0;
  }
  PetscCall(VecResetArray(x_));
  PetscCall(VecResetArray(y_));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::toVec(const double *x, Vec v) const
{
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayWrite(v, &a));
  std::copy(x, x + n_, a);
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::fromVec(Vec v, double *x) const
{
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(v, &a));
  std::copy(a, a + n_, x);
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
