#include "boomdyn/compact_matrix.hpp"

namespace boomdyn {

PetscErrorCode CompactMatrix::update(Mat src)
{
  PetscBool sequential;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)src, MATSEQAIJ, &sequential));
  if (!sequential) {
    copy_.reset();
    source_ = src;
    PetscFunctionReturn(0);
  }
  PetscInt rows, columns;
  const PetscInt *ia, *ja;
  PetscBool done;
  const PetscScalar *a;
  PetscObjectState state;
  PetscObjectId id;
  PetscCall(MatGetSize(src, &rows, &columns));
  PetscCall(MatGetNonzeroState(src, &state));
  // The source by its id, not its address: a matrix made after the last
  // one was destroyed (a new pattern) may get the same address and, made
  // and assembled the same way, the same nonzero state and entry count.
  PetscCall(PetscObjectGetId((PetscObject)src, &id));
  PetscCall(MatGetRowIJ(src, 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_PLIB, "CompactMatrix: no compressed rows of the source");
  PetscCall(MatSeqAIJGetArrayRead(src, &a));
  const PetscInt entries = ia[rows];
  const bool samePositions = copy_ && id == sourceId_ && state == sourceState_ && (PetscInt)kept_.size() == entries;
  // Positions whose values turn zero and nonzero again from one analysis to
  // the next (the paper scene's damping matrix at nearly every analysis)
  // stay in the copy as explicit zeros, up to a sixteenth of its entries:
  // making the copy anew (a PETSc matrix created and destroyed) cost more
  // than the rest of the update. An explicit +0 changes no product bitwise:
  // every product with the copy (LocalBlocks) sums a row from +0 in the
  // order of its entries, and adding +0 or -0 to such a sum leaves it as it
  // is (it is never -0). Values are stored as a + 0.0, which is a for
  // a != 0 and +0 for a = +-0, so that an entry read off the copy
  // (LocalBlocks::columns) is +0 where an exact copy has no entry.
  const PetscInt maxZeros = stored_ / 16;
  bool fits = false;
  PetscInt zeros = 0; // entries of the copy that are zero now
  if (samePositions) {
    // The values into the copy's array (its state changes, so nothing keeps
    // a stale product), and the nonzeros they hold: all of src's nonzeros
    // are among them when src has no more (the copy's positions are a
    // subset of src's). Without branches: the counts over contiguous arrays
    // (vectorized) and the gather into the copy.
    PetscInt all = 0, held = 0;
    for (PetscInt k = 0; k < entries; ++k) all += a[k] != 0.0;
    PetscScalar *v;
    PetscCall(MatSeqAIJGetArrayWrite(copy_, &v));
    for (PetscInt j = 0; j < stored_; ++j) v[j] = a[from_[j]] + 0.0;
    for (PetscInt j = 0; j < stored_; ++j) held += v[j] != 0.0;
    PetscCall(MatSeqAIJRestoreArrayWrite(copy_, &v));
    zeros = stored_ - held;
    fits = all == held && zeros <= maxZeros;
  }
  if (!fits) {
    // Made anew: the nonzeros, and the positions of the previous copy
    // while the explicit zeros stay within the bound (a pattern that
    // alternates between a few sets then settles on their union).
    const bool keepOld = samePositions && zeros <= maxZeros;
    copy_.reset(); // before the arrays it uses change
    source_ = src;
    sourceId_ = id;
    sourceState_ = state;
    kept_.resize(entries);
    rowStart_.resize(rows + 1);
    // Sized for every entry of the source (written at j <= k below; the
    // copy uses the first j), so that a new copy allocates nothing.
    cols_.resize(entries), values_.resize(entries), from_.resize(entries);
    PetscInt j = 0;
    rowStart_[0] = 0;
    for (PetscInt i = 0; i < rows; ++i) {
      for (PetscInt k = ia[i]; k < ia[i + 1]; ++k) {
        const bool keep = a[k] != 0.0 || (keepOld && kept_[k]);
        kept_[k] = keep;
        cols_[j] = ja[k], values_[j] = a[k] + 0.0, from_[j] = k; // overwritten unless kept
        j += keep;
      }
      rowStart_[i + 1] = j;
    }
    stored_ = j;
    PetscCall(MatCreateSeqAIJWithArrays(PetscObjectComm((PetscObject)src), rows, columns, rowStart_.data(),
                                        cols_.data(), values_.data(), copy_.address()));
  }
  PetscCall(MatSeqAIJRestoreArrayRead(src, &a));
  PetscCall(MatRestoreRowIJ(src, 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
