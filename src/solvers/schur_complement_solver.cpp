#include "boomdyn/schur_complement_solver.hpp"

#include "boomdyn/klu_solver.hpp"
#include "boomdyn/log_events.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <unordered_map>
#include <vector>

namespace boomdyn {

namespace {

struct SchurContext {
  MPI_Comm comm = MPI_COMM_NULL;
  PetscInt rowStart = 0, nLocal = 0;
  std::vector<PetscInt> interior, interface; // local row indices
  std::vector<PetscInt> interfaceCounts, interfaceOffsets; // per rank, in the global interface numbering
  PetscInt nInterface = 0;                  // all ranks
  Mat AII = nullptr, AGI = nullptr;         // local blocks of the diagonal part
  Mat AIG = nullptr, AGG = nullptr;
  PetscInt64 matrixId = -1;                  // the operator these blocks were cut from
  // For each block (AII, AGI, AIG, AGG) the position in the diagonal part's
  // value array of each of its entries: a refreshed Jacobian (same operator,
  // same split) refills the blocks by these gathers instead of
  // MatCreateSubMatrix with MAT_REUSE_MATRIX, which searches and sorts every
  // row again (about a tenth of a two-rank step on the 10^5-element boom).
  std::vector<PetscInt> sourceOf[4];
  KSP interiorSolver = nullptr;             // KLU on A_II (boomklu)
  // No W = A_II^{-1} A_IG (nI x nG dense: 19 MB on rank 0 of the 10^5-element
  // boom, solved for every factorization and streamed by every apply). The
  // interior unknowns that A_IG and A_GI touch (J) are ordered last in A_II's
  // factorization, so with A_II = Q U^T L^T P (klu_solver.hpp: boomklu factors
  // the transpose) only the trailing rows of the triangular factors meet the
  // interface: U^{-T} Q^T A_IG (Zhat) is zero before the first J row, and
  // A_GI needs only the trailing part of a back substitution. A solve is one
  // forward and one backward sweep over L and U, as one KLU solve.
  KluFactors lu;                            // A_II's factors, extracted after each factorization
  std::vector<PetscInt> gatherB, scatterX;  // gatherB[m] = interior[Q[m]], scatterX[m] = interior[P[m]]
  PetscInt coupled = 0;                     // |J|
  PetscInt firstRow = 0;                    // first J row of A_IG in Q order (the start of Zhat's nonzeros)
  PetscInt firstColumn = 0;                 // first J column of A_GI in P order (the trailing back substitution)
  std::vector<double> Zhat;                 // rows firstRow.. of U^{-T} Q^T A_IG: (nI - firstRow) x nG, by columns
  std::vector<PetscInt> agiPosition;        // per entry of A_GI: its column's P position - firstColumn
  std::vector<double> work, tailWork;       // nI and nI - firstColumn
  Eigen::PartialPivLU<Eigen::MatrixXd> S;   // factored Schur complement (all ranks)

  PetscErrorCode destroy()
  {
    PetscFunctionBeginUser;
    PetscCall(MatDestroy(&AII));
    PetscCall(MatDestroy(&AGI));
    PetscCall(MatDestroy(&AIG));
    PetscCall(MatDestroy(&AGG));
    matrixId = -1;
    PetscCall(KSPDestroy(&interiorSolver));
    PetscFunctionReturn(0);
  }
};

// sources[k] = the index in Ad's value array of entry k of `block`, the
// submatrix of Ad with rows `rows` and columns `cols` (local indices, both
// ascending) made by MatCreateSubMatrix: the block's row r holds the
// entries of Ad's row rows[r] whose columns are in `cols`, in Ad's order.
// Checked entry by entry against the block (an error, not a wrong copy, if
// MatCreateSubMatrix ever laid a block out differently).
PetscErrorCode blockSources(Mat Ad, const std::vector<PetscInt> &rows, const std::vector<PetscInt> &cols, Mat block,
                            std::vector<PetscInt> *sources)
{
  const PetscInt *ia, *ja, *bi, *bj;
  PetscInt n, nb;
  PetscBool done;
  PetscFunctionBeginUser;
  PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_PLIB, "diagonal block without row pointers");
  PetscCall(MatGetRowIJ(block, 0, PETSC_FALSE, PETSC_FALSE, &nb, &bi, &bj, &done));
  PetscCheck(done && nb == (PetscInt)rows.size(), PETSC_COMM_SELF, PETSC_ERR_PLIB, "Schur block without row pointers");
  // Position of each local column in `cols` (-1: not in the block).
  std::vector<PetscInt> position(n, -1);
  for (std::size_t c = 0; c < cols.size(); ++c) position[cols[c]] = (PetscInt)c;
  sources->assign(bi[nb], -1);
  for (PetscInt r = 0; r < nb; ++r) {
    PetscInt k = bi[r];
    for (PetscInt e = ia[rows[r]]; e < ia[rows[r] + 1]; ++e) {
      const PetscInt c = position[ja[e]];
      if (c < 0) continue;
      PetscCheck(k < bi[r + 1] && bj[k] == c, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "Schur block row %" PetscInt_FMT " does not follow the operator's row", r);
      (*sources)[k++] = e;
    }
    PetscCheck(k == bi[r + 1], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Schur block row %" PetscInt_FMT " has extra entries", r);
  }
  PetscCall(MatRestoreRowIJ(block, 0, PETSC_FALSE, PETSC_FALSE, &nb, &bi, &bj, &done));
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  PetscFunctionReturn(0);
}

// The sweeps over boomklu's extracted factors (KluFactors): A_II x = b is
// U^T w = b(Q), then L^T xbar = w, x(P) = xbar. Row-oriented on the
// transposes, so each position is one dot product with a column of U or L
// (KLU's own transposed solve does the same).

// w[j] for j in [from, n): U^T w = w in place, positions before `from` read as they are.
inline void forwardSweep(const KluFactors &f, PetscInt from, double *w)
{
  const int *up = f.Up.data(), *ui = f.Ui.data();
  const double *ux = f.Ux.data();
  for (PetscInt j = from; j < f.n; ++j) {
    const int end = up[j + 1] - 1; // U's diagonal is the last entry of its column
    double s = w[j];
    for (int p = up[j]; p < end; ++p) s -= ux[p] * w[ui[p]];
    w[j] = s / ux[end];
  }
}

// L^T x = w for positions [to, n) in place, w indexed from `base` (w[i - base]
// is position i); only positions after `to` are read.
inline void backSweep(const KluFactors &f, PetscInt to, PetscInt base, double *w)
{
  const int *lp = f.Lp.data(), *li = f.Li.data();
  const double *lx = f.Lx.data();
  double *x = w - base;
  for (PetscInt j = f.n - 1; j >= to; --j) {
    double s = x[j];
    for (int p = lp[j] + 1; p < lp[j + 1]; ++p) s -= lx[p] * x[li[p]]; // L's unit diagonal comes first
    x[j] = s;
  }
}

PetscErrorCode schurSetUp(PC pc)
{
  SchurContext *ctx;
  Mat A, Ad, Ao;
  const PetscInt *colmap;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &ctx));
  PetscCall(PCGetOperators(pc, nullptr, &A));
  ctx->comm = PetscObjectComm((PetscObject)pc);
  PetscCallMPI(MPI_Comm_size(ctx->comm, &size));
  PetscInt rowEnd;
  PetscCall(MatGetOwnershipRange(A, &ctx->rowStart, &rowEnd));
  ctx->nLocal = rowEnd - ctx->rowStart;
  if (size > 1) {
    PetscCall(MatMPIAIJGetSeqAIJ(A, &Ad, &Ao, &colmap));
  } else {
    Ad = A, Ao = nullptr, colmap = nullptr;
  }

  // Interface rows: those with entries in the off-process block. The
  // Jacobian's pattern is structurally symmetric (each work item adds a full
  // block), so these are also the rows other ranks' rows couple to.
  // Rows with a zero diagonal (multipliers, massless slack coordinates at
  // acceleration level) join the interface too: left in the interior they
  // could make its block singular (a slack row whose multipliers are
  // interface rows has nothing else), and they are few.
  Vec diagonal;
  const PetscScalar *d;
  PetscCall(MatCreateVecs(A, &diagonal, nullptr));
  PetscCall(MatGetDiagonal(A, diagonal));
  PetscCall(VecGetArrayRead(diagonal, &d));
  const std::vector<PetscInt> oldInterior = std::move(ctx->interior), oldInterface = std::move(ctx->interface);
  ctx->interior.clear();
  ctx->interface.clear();
  // The off-process row lengths from Ao's row pointers (one MatGetRow per
  // row cost 2 x 10^5 calls per factorization on the 10^5-element boom).
  const PetscInt *offRows = nullptr;
  PetscInt offCount = 0;
  PetscBool offDone = PETSC_FALSE;
  if (Ao) {
    PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &offCount, &offRows, nullptr, &offDone));
    PetscCheck(offDone && offCount == ctx->nLocal, ctx->comm, PETSC_ERR_PLIB, "off-process block without row pointers");
  }
  for (PetscInt i = 0; i < ctx->nLocal; ++i) {
    const PetscInt offProcess = offRows ? offRows[i + 1] - offRows[i] : 0;
    (offProcess > 0 || d[i] == 0.0 ? ctx->interface : ctx->interior).push_back(i);
  }
  if (Ao) PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &offCount, &offRows, nullptr, &offDone));
  PetscCall(VecRestoreArrayRead(diagonal, &d));
  PetscCall(VecDestroy(&diagonal));
  const PetscMPIInt nG = static_cast<PetscMPIInt>(ctx->interface.size());
  std::vector<PetscMPIInt> counts(size), offsets(size + 1, 0);
  PetscCallMPI(MPI_Allgather(&nG, 1, MPI_INT, counts.data(), 1, MPI_INT, ctx->comm));
  for (int r = 0; r < size; ++r) offsets[r + 1] = offsets[r] + counts[r];
  ctx->interfaceCounts.assign(counts.begin(), counts.end());
  ctx->interfaceOffsets.assign(offsets.begin(), offsets.end());
  ctx->nInterface = offsets[size];
  const PetscMPIInt rank = [&] {
    PetscMPIInt r;
    MPI_Comm_rank(ctx->comm, &r);
    return r;
  }();
  // Global row index of every interface unknown, to number the columns of S.
  std::vector<PetscInt> mine(nG), all(ctx->nInterface);
  for (PetscMPIInt k = 0; k < nG; ++k) mine[k] = ctx->rowStart + ctx->interface[k];
  PetscCallMPI(MPI_Allgatherv(mine.data(), nG, MPIU_INT, all.data(), counts.data(), offsets.data(), MPIU_INT, ctx->comm));
  std::unordered_map<PetscInt, PetscInt> interfaceIndex;
  for (PetscInt k = 0; k < ctx->nInterface; ++k) interfaceIndex[all[k]] = k;

  PetscCall(PetscInfo(pc, "interface Schur complement: %" PetscInt_FMT " unknowns in all, %d on this rank, %zu interior\n",
                      ctx->nInterface, (int)nG, ctx->interior.size()));
  // Interior block, factored with KLU, and the blocks that couple it to this
  // rank's interface. The same operator with the same split (a Jacobian
  // refreshed in place) keeps the blocks and the symbolic factorization.
  PetscInt64 id;
  PetscCall(PetscObjectGetId((PetscObject)A, &id));
  const bool sameSplit = id == ctx->matrixId && ctx->interior == oldInterior && ctx->interface == oldInterface;
  if (!sameSplit) PetscCall(ctx->destroy());
  const MatReuse reuse = sameSplit ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX;
  const PetscInt nI = static_cast<PetscInt>(ctx->interior.size());
  IS isI, isG;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nI, ctx->interior.data(), PETSC_USE_POINTER, &isI));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nG, ctx->interface.data(), PETSC_USE_POINTER, &isG));
  Mat *blocks[4] = {&ctx->AII, &ctx->AGI, &ctx->AIG, &ctx->AGG};
  if (reuse == MAT_INITIAL_MATRIX) {
    PetscCall(MatCreateSubMatrix(Ad, isI, isI, reuse, &ctx->AII));
    PetscCall(MatCreateSubMatrix(Ad, isG, isI, reuse, &ctx->AGI));
    PetscCall(MatCreateSubMatrix(Ad, isI, isG, reuse, &ctx->AIG));
    PetscCall(MatCreateSubMatrix(Ad, isG, isG, reuse, &ctx->AGG));
    PetscCall(blockSources(Ad, ctx->interior, ctx->interior, *blocks[0], &ctx->sourceOf[0]));
    PetscCall(blockSources(Ad, ctx->interface, ctx->interior, *blocks[1], &ctx->sourceOf[1]));
    PetscCall(blockSources(Ad, ctx->interior, ctx->interface, *blocks[2], &ctx->sourceOf[2]));
    PetscCall(blockSources(Ad, ctx->interface, ctx->interface, *blocks[3], &ctx->sourceOf[3]));
  } else {
    const PetscScalar *source;
    PetscCall(MatSeqAIJGetArrayRead(Ad, &source));
    for (int b = 0; b < 4; ++b) {
      PetscScalar *target;
      PetscCall(MatSeqAIJGetArrayWrite(*blocks[b], &target));
      const std::vector<PetscInt> &from = ctx->sourceOf[b];
      for (std::size_t k = 0; k < from.size(); ++k) target[k] = source[from[k]];
      PetscCall(MatSeqAIJRestoreArrayWrite(*blocks[b], &target));
    }
    PetscCall(MatSeqAIJRestoreArrayRead(Ad, &source));
  }
  PetscCall(ISDestroy(&isI));
  PetscCall(ISDestroy(&isG));
  Mat AIG = ctx->AIG, AGG = ctx->AGG;
  if (!sameSplit) {
    // J: the interior unknowns with entries in A_IG's rows or A_GI's columns
    // (the same set for a structurally symmetric pattern), ordered last.
    std::vector<PetscInt> inJ(nI, 0);
    const PetscInt *ia, *ja;
    PetscInt nr;
    PetscBool done;
    PetscCall(MatGetRowIJ(AIG, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
    PetscCheck(done && nr == nI, PETSC_COMM_SELF, PETSC_ERR_PLIB, "interior-interface block without row pointers");
    for (PetscInt i = 0; i < nI; ++i)
      if (ia[i + 1] > ia[i]) inJ[i] = 1;
    PetscCall(MatRestoreRowIJ(AIG, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
    PetscCall(MatGetRowIJ(ctx->AGI, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
    PetscCheck(done && nr == nG, PETSC_COMM_SELF, PETSC_ERR_PLIB, "interface-interior block without row pointers");
    for (PetscInt e = 0; e < ia[nG]; ++e) inJ[ja[e]] = 1;
    PetscCall(MatRestoreRowIJ(ctx->AGI, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
    ctx->coupled = static_cast<PetscInt>(std::count(inJ.begin(), inJ.end(), 1));
    if (nI > 0) PetscCall(kluSetLastUnknowns(ctx->AII, nI, inJ.data()));

    PC ipc;
    PetscCall(KSPCreate(PETSC_COMM_SELF, &ctx->interiorSolver));
    PetscCall(KSPSetType(ctx->interiorSolver, KSPPREONLY));
    PetscCall(KSPGetPC(ctx->interiorSolver, &ipc));
    PetscCall(PCSetType(ipc, PCLU));
    // boomdyn's KLU (klu_solver.hpp): refactorization with the last pivot
    // order while the pattern holds, J last, and its factors extracted below.
    PetscCall(registerKluSolver());
    PetscCall(PCFactorSetMatSolverType(ipc, MATSOLVERBOOMKLU));
    PetscCall(KSPSetErrorIfNotConverged(ctx->interiorSolver, PETSC_TRUE));
    ctx->matrixId = id;
  }
  PetscCall(KSPSetOperators(ctx->interiorSolver, ctx->AII, ctx->AII));
  KluFactors &f = ctx->lu;
  if (nI > 0) {
    PetscCall(KSPSetUp(ctx->interiorSolver));
    PC ipc;
    Mat factor;
    PetscCall(KSPGetPC(ctx->interiorSolver, &ipc));
    PetscCall(PCFactorGetMatrix(ipc, &factor));
    // The values change with every factorization and, after a refused
    // refactorization, the row pivots P too: extracted every time (one pass
    // over L and U, a fraction of the factorization's own work).
    PetscCall(kluExtractFactors(factor, &f));
  } else {
    f = KluFactors{};
  }

  // Positions of J in the factors' orders: rows of A_IG in Q order (fixed by
  // the analysis: CAMD puts them last), columns of A_GI in P order (pivoting
  // may move one earlier, which lengthens the trailing sweeps, not more).
  std::vector<PetscInt> qPosition(nI), pPosition(nI);
  ctx->gatherB.resize(nI), ctx->scatterX.resize(nI);
  for (PetscInt m = 0; m < nI; ++m) {
    qPosition[f.Q[m]] = m, pPosition[f.P[m]] = m;
    ctx->gatherB[m] = ctx->interior[f.Q[m]], ctx->scatterX[m] = ctx->interior[f.P[m]];
  }
  const PetscInt *ia, *ja, *gi, *gj;
  const PetscScalar *aigValues, *agiValues;
  PetscInt nr;
  PetscBool done;
  PetscCall(MatGetRowIJ(AIG, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
  PetscCheck(done && nr == nI, PETSC_COMM_SELF, PETSC_ERR_PLIB, "interior-interface block without row pointers");
  PetscCall(MatGetRowIJ(ctx->AGI, 0, PETSC_FALSE, PETSC_FALSE, &nr, &gi, &gj, &done));
  PetscCheck(done && nr == nG, PETSC_COMM_SELF, PETSC_ERR_PLIB, "interface-interior block without row pointers");
  PetscCall(MatSeqAIJGetArrayRead(AIG, &aigValues));
  PetscCall(MatSeqAIJGetArrayRead(ctx->AGI, &agiValues));
  ctx->firstRow = nI, ctx->firstColumn = nI;
  for (PetscInt i = 0; i < nI; ++i)
    if (ia[i + 1] > ia[i]) ctx->firstRow = std::min(ctx->firstRow, qPosition[i]);
  for (PetscInt e = 0; e < gi[nG]; ++e) ctx->firstColumn = std::min(ctx->firstColumn, pPosition[gj[e]]);
  ctx->agiPosition.resize(gi[nG]);
  for (PetscInt e = 0; e < gi[nG]; ++e) ctx->agiPosition[e] = pPosition[gj[e]] - ctx->firstColumn;
  PetscCall(PetscInfo(ctx->interiorSolver ? (PetscObject)ctx->interiorSolver : (PetscObject)pc, "interior factors: %d in L, %d in U; %" PetscInt_FMT " interior unknowns coupled to the interface, "
                          "first at row %" PetscInt_FMT " and column %" PetscInt_FMT " of %" PetscInt_FMT "\n",
                      nI ? (int)f.Lp[nI] : 0, nI ? (int)f.Up[nI] : 0, ctx->coupled, ctx->firstRow, ctx->firstColumn, nI));

  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(nG, ctx->nInterface);
  for (PetscMPIInt k = 0; k < nG; ++k) {
    PetscInt ncols;
    const PetscInt *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(AGG, k, &ncols, &cols, &vals));
    for (PetscInt c = 0; c < ncols; ++c) rows(k, offsets[rank] + cols[c]) += vals[c];
    PetscCall(MatRestoreRow(AGG, k, &ncols, &cols, &vals));
    if (Ao) {
      PetscCall(MatGetRow(Ao, ctx->interface[k], &ncols, &cols, &vals));
      for (PetscInt c = 0; c < ncols; ++c) {
        const auto it = interfaceIndex.find(colmap[cols[c]]);
        PetscCheck(it != interfaceIndex.end(), ctx->comm, PETSC_ERR_PLIB,
                   "off-process column %" PetscInt_FMT " is not an interface unknown (pattern not symmetric)",
                   colmap[cols[c]]);
        rows(k, it->second) += vals[c];
      }
      PetscCall(MatRestoreRow(Ao, ctx->interface[k], &ncols, &cols, &vals));
    }
  }
  // Zhat = U^{-T} Q^T A_IG from the first J row on, and this rank's rows of
  // S: A_{G_p G} - A_{G_p I_p} (A_II^{-1} A_{I G_p}), where A_GI reads the
  // second factor at J only: the trailing back substitution of each column.
  const PetscInt firstRow = ctx->firstRow, stored = nI - firstRow;
  const PetscInt low = std::min(firstRow, ctx->firstColumn);
  ctx->Zhat.assign(static_cast<std::size_t>(stored) * nG, 0.0);
  ctx->work.assign(nI, 0.0); // zero before `low` for good: the setup's sweeps read it there
  ctx->tailWork.resize(nI - ctx->firstColumn);
  double *w = ctx->work.data();
  for (PetscInt i = 0; i < nI; ++i)
    for (PetscInt e = ia[i]; e < ia[i + 1]; ++e)
      ctx->Zhat[static_cast<std::size_t>(ja[e]) * stored + qPosition[i] - firstRow] = aigValues[e];
  // U's columns from firstRow on without their rows before firstRow, which
  // are zero in every column of Zhat: copied once, since coupled unknowns at
  // both ends of a rank's piece (the clamped node and the cut on rank 0 of
  // the long boom) make those columns of U full, and the forward sweep of
  // each interface column read them whole (rank 0, 20 000 elements, 20
  // steps: the set-up's own instructions 92 M -> 34 M).
  std::vector<int> tailStart(stored + 1, 0), tailRow;
  std::vector<double> tailValue, tailDiagonal(stored);
  for (PetscInt j = firstRow; j < nI; ++j) {
    const int end = f.Up[j + 1] - 1;
    for (int p = f.Up[j]; p < end; ++p)
      if (f.Ui[p] >= firstRow) tailRow.push_back(f.Ui[p] - firstRow), tailValue.push_back(f.Ux[p]);
    tailDiagonal[j - firstRow] = f.Ux[end];
    tailStart[j - firstRow + 1] = static_cast<int>(tailRow.size());
  }
  for (PetscMPIInt k = 0; k < nG && stored > 0; ++k) {
    double *z = ctx->Zhat.data() + static_cast<std::size_t>(k) * stored;
    for (PetscInt j = 0; j < stored; ++j) { // U^T z = z on the trailing rows: forwardSweep from firstRow
      double s = z[j];
      for (int p = tailStart[j]; p < tailStart[j + 1]; ++p) s -= tailValue[p] * z[tailRow[p]];
      z[j] = s / tailDiagonal[j];
    }
    std::fill(w + low, w + firstRow, 0.0); // the last column's back substitution wrote there
    std::copy(z, z + stored, w + firstRow);
    backSweep(f, ctx->firstColumn, 0, w);
    const double *y = w + ctx->firstColumn;
    for (PetscMPIInt r = 0; r < nG; ++r) {
      double s = 0;
      for (PetscInt e = gi[r]; e < gi[r + 1]; ++e) s += agiValues[e] * y[ctx->agiPosition[e]];
      rows(r, offsets[rank] + k) -= s;
    }
  }
  PetscCall(MatSeqAIJRestoreArrayRead(ctx->AGI, &agiValues));
  PetscCall(MatSeqAIJRestoreArrayRead(AIG, &aigValues));
  PetscCall(MatRestoreRowIJ(ctx->AGI, 0, PETSC_FALSE, PETSC_FALSE, &nr, &gi, &gj, &done));
  PetscCall(MatRestoreRowIJ(AIG, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
  // Gather all rows (row-major blocks) and factor S on every rank.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rowMajor = rows, S(ctx->nInterface, ctx->nInterface);
  std::vector<PetscMPIInt> valCounts(size), valOffsets(size);
  for (int r = 0; r < size; ++r)
    valCounts[r] = counts[r] * static_cast<PetscMPIInt>(ctx->nInterface), valOffsets[r] = offsets[r] * static_cast<PetscMPIInt>(ctx->nInterface);
  PetscCallMPI(MPI_Allgatherv(rowMajor.data(), nG * static_cast<PetscMPIInt>(ctx->nInterface), MPIU_SCALAR, S.data(),
                              valCounts.data(), valOffsets.data(), MPIU_SCALAR, ctx->comm));
  if (ctx->nInterface > 0) {
    ctx->S.compute(S);
    // Rows mix forces, scaled constraints and stiff couplings, so a condition
    // estimate says little; a zero or non-finite pivot does.
    const Eigen::VectorXd pivots = ctx->S.matrixLU().diagonal().cwiseAbs();
    PetscCheck(pivots.allFinite() && pivots.minCoeff() > 0, ctx->comm, PETSC_ERR_MAT_LU_ZRPVT,
               "interface Schur complement is singular (smallest pivot %g): the system has no unique solution",
               pivots.size() ? pivots.minCoeff() : 0.0);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode schurApply(PC pc, Vec b, Vec x)
{
  SchurContext *ctx;
  const PetscScalar *barr;
  PetscScalar *xarr;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &ctx));
  const PetscInt nI = static_cast<PetscInt>(ctx->interior.size()), nG = static_cast<PetscInt>(ctx->interface.size());
  const KluFactors &f = ctx->lu;
  double *w = ctx->work.data(), *v = ctx->tailWork.data();
  PetscCall(VecGetArrayRead(b, &barr));
  // w = U^{-T} b_I(Q), all of it; then y = A_II^{-1} b_I at J only: the
  // back substitution from the end down to J's first column position.
  const PetscInt *gatherB = ctx->gatherB.data();
  for (PetscInt m = 0; m < nI; ++m) w[m] = barr[gatherB[m]];
  forwardSweep(f, 0, w);
  const PetscInt firstColumn = ctx->firstColumn;
  std::copy(w + firstColumn, w + nI, v);
  backSweep(f, firstColumn, firstColumn, v);
  // g_p = b_{G_p} - A_{G_p I_p} y, gathered; x_G = S^{-1} g on every rank.
  Eigen::VectorXd g(nG), all(ctx->nInterface);
  {
    const PetscInt *gi, *gj;
    const PetscScalar *vals;
    PetscInt nr;
    PetscBool done;
    PetscCall(MatGetRowIJ(ctx->AGI, 0, PETSC_FALSE, PETSC_FALSE, &nr, &gi, &gj, &done));
    PetscCheck(done && nr == nG, PETSC_COMM_SELF, PETSC_ERR_PLIB, "interface-interior block without row pointers");
    PetscCall(MatSeqAIJGetArrayRead(ctx->AGI, &vals));
    const PetscInt *position = ctx->agiPosition.data();
    for (PetscInt k = 0; k < nG; ++k) {
      double s = barr[ctx->interface[k]];
      for (PetscInt e = gi[k]; e < gi[k + 1]; ++e) s -= vals[e] * v[position[e]];
      g[k] = s;
    }
    PetscCall(MatSeqAIJRestoreArrayRead(ctx->AGI, &vals));
    PetscCall(MatRestoreRowIJ(ctx->AGI, 0, PETSC_FALSE, PETSC_FALSE, &nr, &gi, &gj, &done));
  }
  PetscCall(VecRestoreArrayRead(b, &barr));
  std::vector<PetscMPIInt> counts(ctx->interfaceCounts.begin(), ctx->interfaceCounts.end()),
    offsets(ctx->interfaceOffsets.begin(), ctx->interfaceOffsets.end() - 1);
  PetscCallMPI(MPI_Allgatherv(g.data(), static_cast<PetscMPIInt>(nG), MPIU_SCALAR, all.data(), counts.data(), offsets.data(),
                              MPIU_SCALAR, ctx->comm));
  Eigen::VectorXd xG;
  if (ctx->nInterface > 0) xG = ctx->S.solve(all);
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(ctx->comm, &rank));
  const double *xMine = xG.data() + (ctx->nInterface > 0 ? ctx->interfaceOffsets[rank] : 0);
  // x_I = A_II^{-1} (b_I - A_IG x_G): the forward sweep of the bracket is
  // w - Zhat x_G (nonzero in Zhat's rows only),
  // then the whole back substitution, scattered through P.
  const PetscInt stored = nI - ctx->firstRow;
  for (PetscInt k = 0; k < nG && stored > 0; ++k) {
    const double *z = ctx->Zhat.data() + static_cast<std::size_t>(k) * stored, xk = xMine[k];
    double *wt = w + ctx->firstRow;
    for (PetscInt m = 0; m < stored; ++m) wt[m] -= z[m] * xk;
  }
  backSweep(f, 0, 0, w);
  PetscCall(VecGetArrayWrite(x, &xarr));
  const PetscInt *scatterX = ctx->scatterX.data();
  for (PetscInt m = 0; m < nI; ++m) xarr[scatterX[m]] = w[m];
  for (PetscInt k = 0; k < nG; ++k) xarr[ctx->interface[k]] = xMine[k];
  PetscCall(VecRestoreArrayWrite(x, &xarr));
  if (nI > 0) PetscCall(PetscLogFlops(2.0 * (f.Lp[nI] + f.Up[nI]) + 2.0 * nG * stored));
  PetscFunctionReturn(0);
}

PetscErrorCode schurDestroy(PC pc)
{
  SchurContext *ctx;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &ctx));
  PetscCall(ctx->destroy());
  delete ctx;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode schurComplementLayout(KSP ksp, SchurComplementLayout *layout)
{
  PC pc;
  PetscBool shell;
  SchurContext *ctx;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCSHELL, &shell));
  PetscCheck(shell, PetscObjectComm((PetscObject)ksp), PETSC_ERR_ARG_WRONG, "not a Schur-complement solver");
  PetscCall(PCShellGetContext(pc, &ctx));
  layout->interior = static_cast<PetscInt>(ctx->interior.size());
  layout->interface = static_cast<PetscInt>(ctx->interface.size());
  layout->coupled = ctx->coupled;
  layout->firstRow = ctx->firstRow;
  layout->firstColumn = ctx->firstColumn;
  PetscFunctionReturn(0);
}

PetscErrorCode useSchurComplementSolver(KSP ksp)
{
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, new SchurContext));
  PetscCall(PCShellSetName(pc, "boomdyn interface Schur complement (KLU on rank interiors)"));
  PetscCall(PCShellSetSetUp(pc, schurSetUp));
  PetscCall(PCShellSetApply(pc, schurApply));
  PetscCall(PCShellSetDestroy(pc, schurDestroy));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
