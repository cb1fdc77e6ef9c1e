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
  PetscCall(MatGetSize(src, &rows, &columns));
  PetscCall(MatGetNonzeroState(src, &state));
  PetscCall(MatGetRowIJ(src, 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_PLIB, "CompactMatrix: no compressed rows of the source");
  PetscCall(MatSeqAIJGetArrayRead(src, &a));
  const PetscInt entries = ia[rows];
  bool same = copy_ && src == source_ && state == sourceState_ && (PetscInt)kept_.size() == entries;
  if (same) {
    // Every entry compared, without an early exit: a branch-free loop the
    // compiler vectorizes (the zero pattern holds in three updates of four).
    char changed = 0;
    for (PetscInt k = 0; k < entries; ++k) changed |= (char)((a[k] != 0.0) != (kept_[k] != 0));
    same = !changed;
  }
  if (same) {
    // The same positions: the values only, through the copy's array (its
    // state changes, so nothing keeps a stale product).
    PetscScalar *v;
    PetscCall(MatSeqAIJGetArrayWrite(copy_, &v));
    for (std::size_t j = 0; j < from_.size(); ++j) v[j] = a[from_[j]];
    PetscCall(MatSeqAIJRestoreArrayWrite(copy_, &v));
  } else {
    copy_.reset(); // before the arrays it uses change
    source_ = src;
    sourceState_ = state;
    kept_.resize(entries);
    rowStart_.resize(rows + 1);
    cols_.resize(entries), values_.resize(entries), from_.resize(entries);
    PetscInt j = 0;
    rowStart_[0] = 0;
    for (PetscInt i = 0; i < rows; ++i) {
      for (PetscInt k = ia[i]; k < ia[i + 1]; ++k) {
        const bool keep = a[k] != 0.0;
        kept_[k] = keep;
        cols_[j] = ja[k], values_[j] = a[k], from_[j] = k; // overwritten unless kept
        j += keep;
      }
      rowStart_[i + 1] = j;
    }
    cols_.resize(j), values_.resize(j), from_.resize(j);
    PetscCall(MatCreateSeqAIJWithArrays(PetscObjectComm((PetscObject)src), rows, columns, rowStart_.data(),
                                        cols_.data(), values_.data(), copy_.address()));
  }
  PetscCall(MatSeqAIJRestoreArrayRead(src, &a));
  PetscCall(MatRestoreRowIJ(src, 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
