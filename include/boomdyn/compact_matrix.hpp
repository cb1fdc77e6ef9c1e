// A copy of a matrix without its explicit zeros, for products only (issue
// 18, item 2). The eigen-analysis' matrices share the Jacobian's pattern
// (Assembler::createMatrix: every item's full dof block, so that A - tau B
// is one pattern): on the paper scene 3960 entries, of which M has about
// 1200 and D about 1000 nonzeros, and A about 2550 (the contact and joint
// blocks are sparse). The refinements multiply by them about 150 times per
// analysis. The copy is made on one rank (a sequential AIJ matrix, from the
// source's compressed rows); on more ranks get() is the source itself.
#pragma once

#include "boomdyn/petsc_handle.hpp"

#include <petscmat.h>

#include <vector>

namespace boomdyn {

class CompactMatrix {
public:
  // Copies the nonzeros of src. The copy keeps its pattern while src is the
  // same matrix with the same nonzero positions (the values are copied
  // then); otherwise it is made anew, so that it depends on src's values
  // only (a restarted run gets the same copy). Collective.
  PetscErrorCode update(Mat src);
  // The copy, or the source on more than one rank.
  Mat get() const { return copy_ ? copy_.get() : source_; }
  // Nonzeros of the copy (0 without a copy), for the tests.
  PetscInt nonzeros() const { return static_cast<PetscInt>(cols_.size()); }

private:
  Mat source_ = nullptr;
  PetscObjectState sourceState_ = -1;
  PetscHandle<Mat> copy_;
  std::vector<PetscInt> rowStart_, cols_; // the copy's compressed rows (it uses these arrays)
  std::vector<PetscScalar> values_;
  std::vector<char> kept_;                // per entry of the source: nonzero
  std::vector<PetscInt> from_;            // per entry of the copy: its position in the source
};

} // namespace boomdyn
