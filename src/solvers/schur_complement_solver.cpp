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
  KSP interiorSolver = nullptr;             // KLU on A_II
  Vec bI = nullptr, yI = nullptr;
  // A_II^{-1} A_{I G_p}, by rows: a solve streams it once, row by row, fused
  // with the interior update (see schurApply).
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> W;
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
    PetscCall(VecDestroy(&bI));
    PetscCall(VecDestroy(&yI));
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
    PC ipc;
    PetscCall(KSPCreate(PETSC_COMM_SELF, &ctx->interiorSolver));
    PetscCall(KSPSetType(ctx->interiorSolver, KSPPREONLY));
    PetscCall(KSPGetPC(ctx->interiorSolver, &ipc));
    PetscCall(PCSetType(ipc, PCLU));
    // boomdyn's KLU (klu_solver.hpp): refactorization with the last pivot
    // order while the pattern holds, and all columns of W in one solve below.
    PetscCall(registerKluSolver());
    PetscCall(PCFactorSetMatSolverType(ipc, MATSOLVERBOOMKLU));
    PetscCall(KSPSetErrorIfNotConverged(ctx->interiorSolver, PETSC_TRUE));
    PetscCall(MatCreateVecs(ctx->AII, &ctx->bI, &ctx->yI));
    ctx->matrixId = id;
  }
  PetscCall(KSPSetOperators(ctx->interiorSolver, ctx->AII, ctx->AII));
  if (nI > 0) PetscCall(KSPSetUp(ctx->interiorSolver));

  // W = A_II^{-1} A_IG. The columns of A_IG from one pass over its rows
  // (MatGetColumnVector reads every row once per column: 2.9 x 10^6 row
  // reads per factorization on the 10^5-element boom), then solved all at
  // once with KLU's multi-column solve (each column bitwise what KSPSolve
  // gives), or column by column with another factorization.
  ctx->W.resize(nI, nG);
  if (nI > 0 && nG > 0) {
    Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(nI, nG);
    const PetscInt *ia, *ja;
    PetscInt rowsIG;
    PetscBool done;
    const PetscScalar *values;
    PetscCall(MatGetRowIJ(AIG, 0, PETSC_FALSE, PETSC_FALSE, &rowsIG, &ia, &ja, &done));
    PetscCheck(done && rowsIG == nI, PETSC_COMM_SELF, PETSC_ERR_PLIB, "interior-interface block without row pointers");
    PetscCall(MatSeqAIJGetArrayRead(AIG, &values));
    for (PetscInt i = 0; i < nI; ++i)
      for (PetscInt e = ia[i]; e < ia[i + 1]; ++e) columns(i, ja[e]) = values[e];
    PetscCall(MatSeqAIJRestoreArrayRead(AIG, &values));
    PetscCall(MatRestoreRowIJ(AIG, 0, PETSC_FALSE, PETSC_FALSE, &rowsIG, &ia, &ja, &done));
    PC ipc;
    Mat factor;
    PetscBool solved = PETSC_FALSE;
    PetscCall(KSPGetPC(ctx->interiorSolver, &ipc));
    PetscCall(PCFactorGetMatrix(ipc, &factor));
    PetscCall(kluSolveColumns(factor, nG, nI, columns.data(), &solved));
    for (PetscMPIInt k = 0; k < nG && !solved; ++k) {
      PetscCall(VecPlaceArray(ctx->bI, columns.col(k).data()));
      PetscCall(KSPSolve(ctx->interiorSolver, ctx->bI, ctx->yI));
      PetscCall(VecResetArray(ctx->bI));
      const PetscScalar *y;
      PetscCall(VecGetArrayRead(ctx->yI, &y));
      std::copy(y, y + nI, columns.col(k).data());
      PetscCall(VecRestoreArrayRead(ctx->yI, &y));
    }
    ctx->W = columns; // row-major copy, streamed row by row in schurApply
  }

  // This rank's rows of S: A_{G_p G} - A_{G_p I_p} W (columns G_p only for the second term).
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
    PetscCall(MatGetRow(ctx->AGI, k, &ncols, &cols, &vals));
    for (PetscInt c = 0; c < ncols; ++c)
      for (PetscMPIInt j = 0; j < nG; ++j) rows(k, offsets[rank] + j) -= vals[c] * ctx->W(cols[c], j);
    PetscCall(MatRestoreRow(ctx->AGI, k, &ncols, &cols, &vals));
  }
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
  PetscScalar *xarr, *tmp;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &ctx));
  const PetscInt nI = static_cast<PetscInt>(ctx->interior.size()), nG = static_cast<PetscInt>(ctx->interface.size());
  PetscCall(VecGetArrayRead(b, &barr));
  // y = A_II^{-1} b_I
  if (nI > 0) {
    PetscCall(VecGetArrayWrite(ctx->bI, &tmp));
    for (PetscInt i = 0; i < nI; ++i) tmp[i] = barr[ctx->interior[i]];
    PetscCall(VecRestoreArrayWrite(ctx->bI, &tmp));
    PetscCall(KSPSolve(ctx->interiorSolver, ctx->bI, ctx->yI));
  }
  // g_p = b_{G_p} - A_{G_p I_p} y, gathered; x_G = S^{-1} g on every rank.
  Eigen::VectorXd g(nG), all(ctx->nInterface);
  const PetscScalar *y = nullptr;
  if (nI > 0) PetscCall(VecGetArrayRead(ctx->yI, &y));
  for (PetscInt k = 0; k < nG; ++k) {
    PetscInt ncols;
    const PetscInt *cols;
    const PetscScalar *vals;
    double s = barr[ctx->interface[k]];
    PetscCall(MatGetRow(ctx->AGI, k, &ncols, &cols, &vals));
    for (PetscInt c = 0; c < ncols; ++c) s -= vals[c] * y[cols[c]];
    PetscCall(MatRestoreRow(ctx->AGI, k, &ncols, &cols, &vals));
    g[k] = s;
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
  const Eigen::Map<const Eigen::VectorXd> xMine(xG.data() + (ctx->nInterface > 0 ? ctx->interfaceOffsets[rank] : 0), nG);
  // x_I = y - W x_{G_p}, one pass over W (nI x nG_p: 19 MB on rank 0 of the
  // 10^5-element boom, half of what the interior KLU solve reads), y and x:
  // the product into a temporary and the copy into x made three.
  PetscCall(VecGetArrayWrite(x, &xarr));
  if (nI > 0) {
    const double *w = ctx->W.data(), *xg = xMine.data();
    const PetscInt *interior = ctx->interior.data();
    for (PetscInt i = 0; i < nI; ++i, w += nG) {
      double s = 0;
      for (PetscInt j = 0; j < nG; ++j) s += w[j] * xg[j];
      xarr[interior[i]] = y[i] - s;
    }
    PetscCall(VecRestoreArrayRead(ctx->yI, &y));
  }
  for (PetscInt k = 0; k < nG; ++k) xarr[ctx->interface[k]] = xMine[k];
  PetscCall(VecRestoreArrayWrite(x, &xarr));
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
