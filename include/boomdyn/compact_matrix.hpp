// A copy of a matrix without (most of) its explicit zeros, for products only
// (issue 18, item 2). The eigen-analysis' matrices share the Jacobian's
// pattern (Assembler::createMatrix: every item's full dof block, so that
// A - tau B is one pattern): on the paper scene 3960 entries, of which M has
// about 1200 nonzeros, D about 2550 and A about 2700 (the contact and joint
// blocks are sparse). The refinements multiply by them about 150 times per
// analysis. The copy is made on one rank (a sequential AIJ matrix, from the
// source's compressed rows); on more ranks get() is the source itself.
//
// Positions whose values turn zero and nonzero between updates stay in the
// copy as explicit +0 entries, up to a sixteenth of its entries (update()):
// no product changes bitwise, since every product (LocalBlocks) sums each
// row from +0 in the order of its entries, and adding +-0 to such a sum
// leaves it unchanged. (PETSc's own MatMult pairs a row's terms in its
// unrolled kernels, so its products with the copy may differ in the last
// bits from those with an exact copy; nothing multiplies by it that way.)
#pragma once

#include "boomdyn/petsc_handle.hpp"

#include <petscmat.h>

#include <vector>

namespace boomdyn {

class CompactMatrix {
public:
  // Copies the nonzeros of src. The copy keeps its positions while src is
  // the same matrix, with the same pattern, that has no nonzero outside them
  // and at most a sixteenth of them zero (the values are copied then, the
  // zeros as +0); otherwise it is made anew, with src's nonzeros and, within
  // that bound, the previous positions. The products do not depend on which
  // positions it holds (see above): a restarted run, whose copy may hold
  // fewer explicit zeros, gets bitwise the same products. Collective.
  PetscErrorCode update(Mat src);
  // The copy, or the source on more than one rank.
  Mat get() const { return copy_ ? copy_.get() : source_; }
  // Entries of the copy, explicit zeros included (0 without a copy), for the tests.
  PetscInt nonzeros() const { return copy_ ? stored_ : 0; }

private:
  Mat source_ = nullptr;
  PetscObjectId sourceId_ = -1; // PETSc's object id: unique over the run, unlike the address
  PetscObjectState sourceState_ = -1;
  PetscHandle<Mat> copy_;
  std::vector<PetscInt> rowStart_, cols_; // the copy's compressed rows (it uses these arrays)
  std::vector<PetscScalar> values_;       // (cols_ and values_ sized for the source; the copy uses stored_)
  PetscInt stored_ = 0;                   // entries of the copy
  std::vector<char> kept_;                // per entry of the source: held by the copy
  std::vector<PetscInt> from_;            // per entry of the copy: its position in the source
};

} // namespace boomdyn
