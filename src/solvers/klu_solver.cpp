#include "boomdyn/klu_solver.hpp"

// A MatSolverType is an implementation of PETSc's factor matrix: its
// operations table and data live behind PETSc's private header, as in
// PETSc's own interfaces to external solvers.
#include <petsc/private/matimpl.h>
#include <camd.h>
#include <klu.h>

#include <algorithm>
#include <type_traits>
#include <vector>

namespace boomdyn {

namespace {

static_assert(std::is_same<PetscInt, int>::value, "boomklu calls the int version of KLU (PETSc without 64-bit indices)");
static_assert(std::is_same<PetscScalar, double>::value, "boomklu is for real scalars");

// The factors as plain compressed columns (klu_extract), for the
// several-column solves: KLU's own solve runs four columns at a time with
// scalar arithmetic; these run them as short vectors (up to eight columns
// per pass). Off-diagonal parts only; the unit diagonal of L is implied and
// U's diagonal is kept apart. Extracted on the first several-column solve
// after each numeric factorization.
struct ExtractedFactors {
  bool current = false;
  bool refused = false; // this factorization's extraction failed: KLU solves until the next one
  int n = 0, nblocks = 0;
  std::vector<int> Lp, Li, Up, Ui, Fp, Fi, P, Q, R;
  std::vector<double> Lx, Ux, Fx, Udiag;
  std::vector<double> work; // the columns being solved, row by row
};

// KLU factors the compressed columns it is given. PETSc's AIJ rows read as
// columns are A^T, so KLU factors A^T, A x = b is KLU's transposed solve and
// A^T x = b its plain one (as in PETSc's interface).
struct KluFactor {
  klu_common common;
  klu_symbolic *symbolic = nullptr;
  klu_numeric *numeric = nullptr;
  PetscBool refactor = PETSC_TRUE;
  PetscReal growthDrop = 1e-2;
  double fullGrowth = 0; // reciprocal pivot growth of the last klu_factor
  bool orderedLast = false; // analysed with kluSetLastUnknowns' constraint (one block, no BTF)
  KluFactorCounts counts;
  ExtractedFactors extracted;

  void release()
  {
    if (numeric) klu_free_numeric(&numeric, &common);
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
};

KluFactor *data(Mat F) { return static_cast<KluFactor *>(F->data); }

// The CSR arrays of a sequential AIJ matrix, borrowed.
struct Rows {
  Mat A;
  PetscInt n = 0;
  const PetscInt *ia = nullptr, *ja = nullptr;
  const PetscScalar *a = nullptr;
  PetscErrorCode borrow(Mat m)
  {
    PetscBool done;
    PetscFunctionBeginUser;
    A = m;
    PetscCall(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "boomklu: the matrix does not give its compressed rows");
    PetscCall(MatSeqAIJGetArrayRead(A, &a));
    PetscFunctionReturn(0);
  }
  PetscErrorCode giveBack()
  {
    PetscBool done;
    PetscFunctionBeginUser;
    PetscCall(MatSeqAIJRestoreArrayRead(A, &a));
    PetscCall(MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    PetscFunctionReturn(0);
  }
  int *p() const { return const_cast<int *>(ia); }
  int *i() const { return const_cast<int *>(ja); }
  double *x() const { return const_cast<double *>(a); }
};

PetscErrorCode solveInPlace(Mat F, PetscInt columns, PetscInt ld, double *x, bool transposed)
{
  KluFactor *lu = data(F);
  PetscFunctionBeginUser;
  const int ok = transposed ? klu_solve(lu->symbolic, lu->numeric, ld, columns, x, &lu->common)
                            : klu_tsolve(lu->symbolic, lu->numeric, ld, columns, x, &lu->common);
  PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_LIB, "boomklu: KLU solve failed (status %d)", lu->common.status);
  PetscFunctionReturn(0);
}

PetscErrorCode solveVec(Mat F, Vec b, Vec x, bool transposed)
{
  PetscScalar *xa;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(b, x));
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(VecGetArray(x, &xa));
  PetscCall(solveInPlace(F, 1, n, xa, transposed));
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(PetscLogFlops(2.0 * (data(F)->numeric->lnz + data(F)->numeric->unz)));
  PetscFunctionReturn(0);
}

PetscErrorCode matSolve(Mat F, Vec b, Vec x) { return solveVec(F, b, x, false); }
PetscErrorCode matSolveTranspose(Mat F, Vec b, Vec x) { return solveVec(F, b, x, true); }

// Dense right-hand sides B, solutions X (MatMatSolve).
PetscErrorCode matMatSolve(Mat F, Mat B, Mat X)
{
  const PetscScalar *b;
  PetscScalar *x;
  PetscInt n, k, ldb, ldx;
  PetscFunctionBeginUser;
  PetscCall(MatGetSize(B, &n, &k));
  PetscCall(MatDenseGetLDA(B, &ldb));
  PetscCall(MatDenseGetLDA(X, &ldx));
  PetscCall(MatDenseGetArrayRead(B, &b));
  PetscCall(MatDenseGetArrayWrite(X, &x));
  for (PetscInt j = 0; j < k; ++j) PetscCall(PetscArraycpy(x + j * ldx, b + j * ldb, n));
  PetscCall(MatDenseRestoreArrayRead(B, &b));
  PetscCall(solveInPlace(F, k, ldx, x, false));
  PetscCall(MatDenseRestoreArrayWrite(X, &x));
  PetscFunctionReturn(0);
}

// KLU running out of memory is no breakdown of the factorization: it is
// PETSC_ERR_MEM (an out-of-memory message), everything else PETSC_ERR_LIB
// (which NewtonSolver::factor reports as a singular matrix).
PetscErrorCode kluErrorCode(int status) { return status == KLU_OUT_OF_MEMORY ? PETSC_ERR_MEM : PETSC_ERR_LIB; }

// Full factorization with partial pivoting; records the pivot growth that
// later refactorizations are measured against.
PetscErrorCode factorFully(Mat F, const Rows &rows)
{
  KluFactor *lu = data(F);
  PetscFunctionBeginUser;
  if (lu->numeric) klu_free_numeric(&lu->numeric, &lu->common);
  lu->numeric = klu_factor(rows.p(), rows.i(), rows.x(), lu->symbolic, &lu->common);
  ++lu->counts.full;
  // A library error, as from PETSc's interface: the callers turn it into a
  // message about the model (NewtonSolver::factor).
  PetscCheck(lu->numeric, PETSC_COMM_SELF, kluErrorCode(lu->common.status),
             "boomklu: KLU factorization failed (status %d%s, column %d)", lu->common.status,
             lu->common.status == KLU_SINGULAR        ? ": singular"
             : lu->common.status == KLU_OUT_OF_MEMORY ? ": cannot allocate the memory it needs"
                                                      : "",
             lu->common.singular_col);
  PetscCheck(klu_rgrowth(rows.p(), rows.i(), rows.x(), lu->symbolic, lu->numeric, &lu->common), PETSC_COMM_SELF,
             PETSC_ERR_LIB, "boomklu: KLU pivot growth failed (status %d)", lu->common.status);
  lu->fullGrowth = lu->common.rgrowth;
  PetscFunctionReturn(0);
}

PetscErrorCode factorNumeric(Mat F, Mat A, const MatFactorInfo *)
{
  KluFactor *lu = data(F);
  Rows rows;
  PetscFunctionBeginUser;
  F->factorerrortype = MAT_FACTOR_NOERROR;
  lu->extracted.current = lu->extracted.refused = false;
  PetscCall(rows.borrow(A));
  bool done = false;
  if (lu->refactor && lu->numeric) {
    // Same pattern (PETSc calls the symbolic phase again otherwise), so the
    // pivot order of the last factorization applies; kept while the pivots
    // stay as safe as those partial pivoting chose (rgrowth: the smallest
    // ratio over the columns of max |A_ij| to max |U_ij|).
    if (klu_refactor(rows.p(), rows.i(), rows.x(), lu->symbolic, lu->numeric, &lu->common) &&
        klu_rgrowth(rows.p(), rows.i(), rows.x(), lu->symbolic, lu->numeric, &lu->common) &&
        lu->common.rgrowth >= lu->growthDrop * lu->fullGrowth) {
      ++lu->counts.refactors;
      done = true;
    } else {
      ++lu->counts.rejected;
      PetscCall(PetscInfo(F, "refactorization rejected (pivot growth %g, last full factorization %g): factoring again\n",
                          lu->common.rgrowth, lu->fullGrowth));
    }
  }
  if (!done) PetscCall(factorFully(F, rows));
  PetscCall(rows.giveBack());
  F->ops->solve = matSolve;
  F->ops->solvetranspose = matSolveTranspose;
  F->ops->matsolve = matMatSolve;
  F->assembled = PETSC_TRUE;
  F->preallocated = PETSC_TRUE;
  PetscFunctionReturn(0);
}

// The name under which kluSetLastUnknowns() composes its marks on a matrix.
const char *const lastUnknownsKey = "boomklu_last_unknowns";

// KLU's user ordering (klu_common.ordering = 3): CAMD with the constraint
// set in user_data (0 first, 1 last). Returns KLU's estimate of nnz(L) (as
// its AMD branch), 0 on failure.
int camdLast(int n, int *Ap, int *Ai, int *perm, klu_common *common)
{
  const auto *last = static_cast<const std::vector<int> *>(common->user_data);
  double control[CAMD_CONTROL], info[CAMD_INFO];
  camd_defaults(control);
  const int status = camd_order(n, Ap, Ai, perm, control, info, last->data());
  if (status != CAMD_OK && status != CAMD_OK_BUT_JUMBLED) return 0;
  return std::max(1, static_cast<int>(info[CAMD_LNZ]) + n);
}

PetscErrorCode destroyLastUnknowns(void *p)
{
  delete static_cast<std::vector<int> *>(p);
  return 0;
}

PetscErrorCode factorSymbolic(Mat F, Mat A, IS, IS, const MatFactorInfo *)
{
  KluFactor *lu = data(F);
  Rows rows;
  PetscFunctionBeginUser;
  lu->release();
  // Unknowns that kluSetLastUnknowns() marked on A go last: CAMD on the
  // whole matrix, without BTF (whose blocks the extracted factors of
  // kluExtractFactors() would leave out) and its off-diagonal part.
  PetscContainer container = nullptr;
  std::vector<int> *last = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)A, lastUnknownsKey, (PetscObject *)&container));
  if (container) PetscCall(PetscContainerGetPointer(container, (void **)&last));
  PetscCall(rows.borrow(A));
  PetscCheck(!last || (PetscInt)last->size() == rows.n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
             "boomklu: %zu unknowns marked to go last on a matrix of %" PetscInt_FMT " rows", last ? last->size() : 0,
             rows.n);
  lu->orderedLast = last != nullptr;
  lu->common.btf = last ? 0 : 1;
  lu->common.ordering = last ? 3 : 0;
  lu->common.user_order = last ? camdLast : nullptr;
  lu->common.user_data = last;
  lu->symbolic = klu_analyze(rows.n, rows.p(), rows.i(), &lu->common);
  lu->common.user_data = nullptr; // the container may go before the factor
  PetscCall(rows.giveBack());
  PetscCheck(lu->symbolic, PETSC_COMM_SELF, kluErrorCode(lu->common.status), "boomklu: KLU analysis failed (status %d%s)",
             lu->common.status, lu->common.status == KLU_OUT_OF_MEMORY ? ": cannot allocate the memory it needs" : "");
  F->ops->lufactornumeric = factorNumeric;
  PetscFunctionReturn(0);
}

PetscErrorCode factorView(Mat F, PetscViewer viewer)
{
  PetscBool ascii;
  PetscViewerFormat format;
  const KluFactor *lu = data(F);
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerGetFormat(viewer, &format));
  if (format != PETSC_VIEWER_ASCII_INFO && format != PETSC_VIEWER_ASCII_INFO_DETAIL) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "boomklu (SuiteSparse KLU with refactorization):\n"));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  refactor %s, growth drop %g\n", lu->refactor ? "on" : "off",
                                   (double)lu->growthDrop));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  factorizations: %d full, %d refactorizations, %d rejected\n",
                                   lu->counts.full, lu->counts.refactors, lu->counts.rejected));
  if (lu->numeric)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  nonzeros in L %d, in U %d, off-diagonal blocks %d\n", lu->numeric->lnz,
                                     lu->numeric->unz, lu->numeric->nzoff));
  PetscFunctionReturn(0);
}

// What PCSetUp_LU logs about the factor (fill).
PetscErrorCode factorInfo(Mat F, MatInfoType, MatInfo *info)
{
  const KluFactor *lu = data(F);
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(info, sizeof(*info)));
  info->block_size = 1.0;
  if (lu->numeric) info->nz_used = info->nz_allocated = (PetscLogDouble)(lu->numeric->lnz + lu->numeric->unz);
  PetscFunctionReturn(0);
}

PetscErrorCode factorDestroy(Mat F)
{
  PetscFunctionBeginUser;
  KluFactor *lu = data(F);
  if (lu) lu->release();
  delete lu;
  F->data = nullptr;
  PetscCall(PetscObjectComposeFunction((PetscObject)F, "MatFactorGetSolverType_C", nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode factorSolverType(Mat, MatSolverType *type)
{
  PetscFunctionBeginUser;
  *type = MATSOLVERBOOMKLU;
  PetscFunctionReturn(0);
}

// MatGetFactor() for "boomklu": an empty factor matrix of A's size.
PetscErrorCode getFactor(Mat A, MatFactorType type, Mat *F)
{
  Mat B;
  PetscInt m, n;
  PetscFunctionBeginUser;
  PetscCheck(type == MAT_FACTOR_LU, PetscObjectComm((PetscObject)A), PETSC_ERR_SUP, "boomklu does LU only");
  PetscCall(MatGetSize(A, &m, &n));
  PetscCall(MatCreate(PetscObjectComm((PetscObject)A), &B));
  PetscCall(MatSetSizes(B, PETSC_DECIDE, PETSC_DECIDE, m, n));
  PetscCall(PetscStrallocpy(MATSOLVERBOOMKLU, &((PetscObject)B)->type_name));
  PetscCall(MatSetUp(B));
  auto *lu = new KluFactor;
  klu_defaults(&lu->common);
  // No row scaling, as PETSc's interface (whose 0 also has KLU check the
  // compressed columns for every factorization: 68 k instructions at 216
  // unknowns, 96 M on the paper scene); an assembled AIJ matrix has sorted
  // rows without duplicates, so -1: no scaling, no check.
  lu->common.scale = -1;
  B->data = lu;
  B->ops->lufactorsymbolic = factorSymbolic;
  B->ops->destroy = factorDestroy;
  B->ops->view = factorView;
  B->ops->getinfo = factorInfo;
  PetscCall(PetscObjectComposeFunction((PetscObject)B, "MatFactorGetSolverType_C", factorSolverType));
  B->factortype = MAT_FACTOR_LU;
  B->assembled = PETSC_TRUE; // MatView (-ksp_view) asks
  B->preallocated = PETSC_TRUE;
  B->canuseordering = PETSC_FALSE; // KLU orders (BTF, AMD) by itself
  PetscCall(PetscFree(B->solvertype));
  PetscCall(PetscStrallocpy(MATSOLVERBOOMKLU, &B->solvertype));
  PetscCall(PetscStrallocpy(MATORDERINGEXTERNAL, (char **)&B->preferredordering[MAT_FACTOR_LU]));
  // Refactorization carries the pivot order of an earlier matrix, history
  // that a checkpoint does not hold, just as the reused Jacobian of modified
  // Newton: a restarted run agrees to the Newton tolerance, not bitwise. So
  // its default follows -boom_jacobian_reuse, and with that off (the
  // bitwise-restart mode, docs/checkpoints) every factorization pivots.
  PetscBool reuse = PETSC_TRUE, set;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-boom_jacobian_reuse", &reuse, &set));
  lu->refactor = reuse;
  PetscOptionsBegin(PetscObjectComm((PetscObject)A), ((PetscObject)A)->prefix, "boomklu options", "Mat");
  PetscCall(PetscOptionsBool("-mat_boomklu_refactor", "Reuse the last pivot order (klu_refactor) while the pattern holds",
                             "docs/performance.md", lu->refactor, &lu->refactor, nullptr));
  PetscCall(PetscOptionsReal("-mat_boomklu_growth_drop",
                             "Factor again with pivoting when a refactorization's reciprocal pivot growth falls below "
                             "this times the last full factorization's",
                             "docs/performance.md", lu->growthDrop, &lu->growthDrop, nullptr));
  PetscOptionsEnd();
  PetscCheck(lu->growthDrop >= 0 && lu->growthDrop <= 1, PetscObjectComm((PetscObject)A), PETSC_ERR_USER_INPUT,
             "-mat_boomklu_growth_drop must be in [0, 1], got %g", (double)lu->growthDrop);
  *F = B;
  PetscFunctionReturn(0);
}

bool registered = false;

PetscErrorCode forgetRegistration()
{
  registered = false; // PetscFinalize() empties the registry
  return 0;
}

bool isKluFactor(Mat F)
{
  return F && F->factortype == MAT_FACTOR_LU && F->ops->destroy == factorDestroy && F->data;
}

} // namespace

PetscErrorCode registerKluSolver()
{
  PetscFunctionBeginUser;
  if (registered) PetscFunctionReturn(0);
  PetscCall(MatSolverTypeRegister(MATSOLVERBOOMKLU, MATSEQAIJ, MAT_FACTOR_LU, getFactor));
  PetscCall(PetscRegisterFinalize(forgetRegistration));
  registered = true;
  PetscFunctionReturn(0);
}

namespace {

// Columns per pass of the several-column solve. A pass costs about the
// same for any width up to eight (one entry's index and value serve all
// columns; eight doubles are two AVX2 vectors), so fewer columns are padded
// with zero columns that are solved and dropped.
constexpr int kSolveWidth = 8;

// Fills lu->extracted from the numeric factorization: klu_extract into
// compressed columns, then the diagonals taken out of L (unit) and U (kept
// in Udiag), each column's other entries in their stored order, which is
// the order KLU's own solves visit them in. False when the factors do not
// have the expected form (then KLU solves).
bool extractFactors(KluFactor *lu)
{
  ExtractedFactors &e = lu->extracted;
  const klu_numeric *num = lu->numeric;
  const int n = num->n;
  // Sized once per pattern (resize keeps the storage): the extraction
  // writes every entry, and the compaction below runs in place, since a
  // column's off-diagonal entries never move right.
  e.Lp.resize(n + 1), e.Li.resize(num->lnz), e.Lx.resize(num->lnz);
  e.Up.resize(n + 1), e.Ui.resize(num->unz), e.Ux.resize(num->unz), e.Udiag.resize(n);
  e.Fp.resize(n + 1), e.Fi.resize(std::max(1, num->nzoff)), e.Fx.resize(std::max(1, num->nzoff));
  e.P.resize(n), e.Q.resize(n), e.R.resize(n + 1);
  if (!klu_extract(lu->numeric, lu->symbolic, e.Lp.data(), e.Li.data(), e.Lx.data(), e.Up.data(), e.Ui.data(),
                   e.Ux.data(), e.Fp.data(), e.Fi.data(), e.Fx.data(), e.P.data(), e.Q.data(), nullptr, e.R.data(),
                   &lu->common))
    return false;
  e.n = n;
  e.nblocks = num->nblocks;
  int l = 0, u = 0, lBegin = 0, uBegin = 0; // lBegin, uBegin: the extracted column starts (Lp, Up are rewritten)
  for (int k = 0; k < n; ++k) {
    int diagonals = 0;
    const int lEnd = e.Lp[k + 1], uEnd = e.Up[k + 1];
    for (int p = lBegin; p < lEnd; ++p) {
      if (e.Li[p] == k) {
        if (e.Lx[p] != 1.0) return false;
        ++diagonals;
      } else {
        e.Li[l] = e.Li[p], e.Lx[l++] = e.Lx[p];
      }
    }
    for (int p = uBegin; p < uEnd; ++p) {
      if (e.Ui[p] == k) {
        e.Udiag[k] = e.Ux[p];
        ++diagonals;
      } else {
        e.Ui[u] = e.Ui[p], e.Ux[u++] = e.Ux[p];
      }
    }
    if (diagonals != 2) return false;
    e.Lp[k + 1] = l, e.Up[k + 1] = u;
    lBegin = lEnd, uBegin = uEnd;
  }
  // Row indices as offsets into the row-major work block (kSolveWidth
  // columns per row): the solve's inner loop then addresses without
  // multiplying.
  for (int p = 0; p < l; ++p) e.Li[p] *= kSolveWidth;
  for (int p = 0; p < u; ++p) e.Ui[p] *= kSolveWidth;
  for (int p = 0; p < e.Fp[n]; ++p) e.Fi[p] *= kSolveWidth;
  e.current = true;
  return true;
}

// x[c] = X[W k + c] - sum_p v[p] X[i[p] + c], the products subtracted one
// by one in the stored order p = begin, ..., end - 1 (klu_tsolve's order).
inline void rowMinusProducts(const double *X, int k, int begin, int end, const int *i, const double *v,
                             double x[kSolveWidth])
{
  constexpr int W = kSolveWidth;
  for (int c = 0; c < W; ++c) x[c] = X[W * k + c];
  for (int p = begin; p < end; ++p) {
    const double a = v[p];
    const double *xi = X + i[p];
    for (int c = 0; c < W; ++c) x[c] -= a * xi[c];
  }
}

// A x = b for kSolveWidth = W columns held row by row in X (X[W i + c]:
// row i of column c), permuted: KLU factored A^T (P A^T Q = L U + F, no scaling), so
// A = Q (L U + F)^T P and the solve is KLU's transposed one, block by block:
// the off-diagonal part, then U^T (forward) and L^T (backward), every
// column with exactly the operations of klu_tsolve in the same order (each
// result bitwise klu_tsolve's); the W columns side by side as vectors.
void transposedSolve(const ExtractedFactors &e, double *X)
{
  constexpr int W = kSolveWidth;
  double x[W];
  for (int block = 0; block < e.nblocks; ++block) {
    const int k1 = e.R[block], k2 = e.R[block + 1];
    if (block > 0)
      for (int k = k1; k < k2; ++k) {
        rowMinusProducts(X, k, e.Fp[k], e.Fp[k + 1], e.Fi.data(), e.Fx.data(), x);
        for (int c = 0; c < W; ++c) X[W * k + c] = x[c];
      }
    for (int k = k1; k < k2; ++k) { // U^T, forward
      rowMinusProducts(X, k, e.Up[k], e.Up[k + 1], e.Ui.data(), e.Ux.data(), x);
      const double d = e.Udiag[k];
      for (int c = 0; c < W; ++c) X[W * k + c] = x[c] / d;
    }
    for (int k = k2 - 1; k >= k1; --k) { // L^T, backward
      rowMinusProducts(X, k, e.Lp[k], e.Lp[k + 1], e.Li.data(), e.Lx.data(), x);
      for (int c = 0; c < W; ++c) X[W * k + c] = x[c];
    }
  }
}

// `used` <= kSolveWidth columns of x (column-major, leading dimension ld) through the
// row-major work block: gathered by Q, solved, scattered by P; the work
// block's other columns are zero (solved and dropped).
void solveChunk(const ExtractedFactors &e, int used, PetscInt ld, double *x, std::vector<double> &work)
{
  constexpr int W = kSolveWidth;
  const int n = e.n;
  work.resize((std::size_t)W * n);
  double *X = work.data();
  for (int c = 0; c < used; ++c) {
    const double *b = x + c * ld;
    for (int k = 0; k < n; ++k) X[W * k + c] = b[e.Q[k]];
  }
  for (int c = used; c < W; ++c)
    for (int k = 0; k < n; ++k) X[W * k + c] = 0.0;
  transposedSolve(e, X);
  for (int c = 0; c < used; ++c) {
    double *b = x + c * ld;
    for (int k = 0; k < n; ++k) b[e.P[k]] = X[W * k + c];
  }
}

} // namespace

PetscErrorCode kluSolveColumns(Mat factor, PetscInt columns, PetscInt ld, double *x, PetscBool *done)
{
  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  if (!isKluFactor(factor) || !data(factor)->numeric || factor->factorerrortype) PetscFunctionReturn(0);
  KluFactor *lu = data(factor);
  // Several columns through the extracted factors (about half of KLU's
  // instructions per column and entry at eight columns); one column, or
  // factors of another form, through KLU. A factorization whose extraction
  // failed is not extracted again for every call: KLU solves until the next.
  ExtractedFactors &e = lu->extracted;
  if (columns > 1 && lu->common.scale <= 0 && !e.current && !e.refused) e.refused = !extractFactors(lu);
  if (columns > 1 && lu->common.scale <= 0 && e.current) {
    for (PetscInt c = 0; c < columns; c += kSolveWidth)
      solveChunk(e, (int)std::min<PetscInt>(kSolveWidth, columns - c), ld, x + c * ld, e.work);
  } else if (columns > 0) {
    PetscCall(solveInPlace(factor, columns, ld, x, false));
  }
  PetscCall(PetscLogFlops(2.0 * columns * (data(factor)->numeric->lnz + data(factor)->numeric->unz)));
  *done = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode kluSetLastUnknowns(Mat A, PetscInt n, const PetscInt *last)
{
  PetscContainer container;
  PetscFunctionBeginUser;
  auto *marks = new std::vector<int>(last, last + n);
  for (int &m : *marks) m = m ? 1 : 0;
  PetscCall(PetscContainerCreate(PETSC_COMM_SELF, &container));
  PetscCall(PetscContainerSetPointer(container, marks));
  PetscCall(PetscContainerSetUserDestroy(container, destroyLastUnknowns));
  PetscCall(PetscObjectCompose((PetscObject)A, lastUnknownsKey, (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container)); // A holds it now
  PetscFunctionReturn(0);
}

PetscErrorCode kluExtractFactors(Mat factor, KluFactors *f)
{
  PetscFunctionBeginUser;
  PetscCheck(isKluFactor(factor) && data(factor)->numeric && !factor->factorerrortype, PETSC_COMM_SELF,
             PETSC_ERR_ARG_WRONGSTATE, "boomklu: no numeric factorization to extract");
  KluFactor *lu = data(factor);
  // One block and no scaling: L and U are then the whole factorization.
  PetscCheck(lu->orderedLast && lu->symbolic->nblocks == 1 && !lu->numeric->Rs, PETSC_COMM_SELF,
             PETSC_ERR_ARG_WRONGSTATE,
             "boomklu: only a factorization analysed with kluSetLastUnknowns (one block, unscaled) can be extracted");
  const int n = lu->symbolic->n;
  f->n = n;
  f->Lp.resize(n + 1), f->Up.resize(n + 1), f->P.resize(n), f->Q.resize(n);
  f->Li.resize(lu->numeric->lnz), f->Lx.resize(lu->numeric->lnz);
  f->Ui.resize(lu->numeric->unz), f->Ux.resize(lu->numeric->unz);
  PetscCheck(klu_extract(lu->numeric, lu->symbolic, f->Lp.data(), f->Li.data(), f->Lx.data(), f->Up.data(), f->Ui.data(),
                         f->Ux.data(), nullptr, nullptr, nullptr, f->P.data(), f->Q.data(), nullptr, nullptr, &lu->common),
             PETSC_COMM_SELF, PETSC_ERR_LIB, "boomklu: klu_extract failed (status %d)", lu->common.status);
  PetscFunctionReturn(0);
}

PetscErrorCode kluFactorCounts(Mat factor, KluFactorCounts *counts, PetscBool *isKlu)
{
  PetscFunctionBeginUser;
  *isKlu = isKluFactor(factor) ? PETSC_TRUE : PETSC_FALSE;
  *counts = *isKlu ? data(factor)->counts : KluFactorCounts{};
  if (*isKlu && data(factor)->numeric) counts->offDiagonal = data(factor)->numeric->nzoff;
  PetscFunctionReturn(0);
}

} // namespace boomdyn
