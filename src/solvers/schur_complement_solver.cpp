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
  // Adopted rows (see adoptRows): rows of another rank r whose columns are
  // all this rank's or the group's own (the clamp's multipliers, numbered
  // last on the last rank, with the clamped node on rank 0). This rank takes
  // them into its interior as extended local rows nLocal + k; r drops them.
  MPI_Comm p2p = MPI_COMM_NULL;               // a duplicate of comm for the point-to-point messages
  std::vector<PetscInt> adoptedGlobal;        // global rows adopted by this rank, grouped by owner
  std::vector<PetscMPIInt> adoptedFrom;       // owners with rows adopted here, ascending
  std::vector<PetscInt> adoptedFromOffset;    // their ranges in adoptedGlobal (size + 1)
  std::vector<PetscInt> adoptedPattern;       // row lengths and global columns of the adopted rows (the split check)
  std::vector<PetscInt> givenLocal;           // local rows this rank's neighbours adopted, grouped by adopter
  std::vector<PetscMPIInt> givenTo;           // adopters, ascending
  std::vector<PetscInt> givenToOffset;        // their ranges in givenLocal
  std::vector<PetscInt> aoAdoptedPosition;    // positions in Ao's value array of this rank's entries in adopted columns
  std::vector<double> extra;                  // values from outside Ad: Ao at those positions, then the adopted rows' values
  PetscInt adNonzeros = 0;                    // sourceOf indices >= this are extra[index - adNonzeros]
  std::vector<double> adoptedB, adoptedX, givenB, givenX; // apply buffers
  std::vector<MPI_Request> requests;

  PetscErrorCode destroy()
  {
    PetscFunctionBeginUser;
    PetscCall(MatDestroy(&AII));
    PetscCall(MatDestroy(&AGI));
    PetscCall(MatDestroy(&AIG));
    PetscCall(MatDestroy(&AGG));
    matrixId = -1;
    PetscCall(KSPDestroy(&interiorSolver));
    adNonzeros = 0;
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

// Rows received from the ranks whose rows this rank adopts, at this set-up.
struct AdoptedRows {
  std::vector<PetscInt> length, columns; // per row, then the global columns of all rows
  std::vector<double> values;
};

constexpr int kTagPattern = 1, kTagValues = 2, kTagB = 3, kTagX = 4, kTagAnswer = 5;

// Adoption (collective on every rank of the PC): a row owned by rank r with
// off-process entries goes to rank p when every column of it is either
// owned by p or one of the rows of its group, the group being the rows of r
// adopted together (closed under their on-process columns). The clamp's
// multipliers are such a group: numbered last, they are the last rank's
// rows, but their columns are the clamped node's coordinates on rank 0 and
// themselves (stored zeros). Left with r they put rank 0's interior in
// contact with the interface at both ends of its piece (an arrow in its
// factors); adopted by p they are interior rows of p like the rest of the
// clamp, and p's rows that couple to them only can be interior too. Rows
// whose off-process columns are themselves candidates of another rank stay
// (no two ranks adopt each other's rows). Fills ctx's adoption lists and
// receives the adopted rows' patterns and values (sent at every set-up, they
// change with every factorization).
PetscErrorCode adoptRows(SchurContext *ctx, Mat A, Mat Ad, Mat Ao, const PetscInt *colmap, AdoptedRows *in)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(ctx->comm, &size));
  PetscCallMPI(MPI_Comm_rank(ctx->comm, &rank));
  ctx->adoptedGlobal.clear(), ctx->adoptedFrom.clear(), ctx->adoptedFromOffset.assign(1, 0);
  ctx->givenLocal.clear(), ctx->givenTo.clear(), ctx->givenToOffset.assign(1, 0);
  *in = AdoptedRows{};
  if (size == 1 || !Ao) PetscFunctionReturn(0);
  if (ctx->p2p == MPI_COMM_NULL) PetscCallMPI(MPI_Comm_dup(ctx->comm, &ctx->p2p));
  const PetscInt *ranges;
  PetscCall(MatGetOwnershipRanges(A, &ranges));
  const auto owner = [&](PetscInt g) {
    return static_cast<PetscMPIInt>(std::upper_bound(ranges, ranges + size + 1, g) - ranges - 1);
  };
  const PetscInt nLocal = ctx->nLocal, rowStart = ctx->rowStart;
  const PetscInt *ai, *aj, *oi, *oj;
  PetscInt n;
  PetscBool done;
  PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &n, &ai, &aj, &done));
  PetscCheck(done && n == nLocal, PETSC_COMM_SELF, PETSC_ERR_PLIB, "diagonal block without row pointers");
  PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &n, &oi, &oj, &done));
  PetscCheck(done && n == nLocal, PETSC_COMM_SELF, PETSC_ERR_PLIB, "off-process block without row pointers");
  std::vector<PetscMPIInt> target(nLocal, -1);
  std::vector<PetscInt> candidates; // local rows with a target
  for (PetscInt i = 0; i < nLocal; ++i) {
    if (oi[i + 1] == oi[i]) continue;
    PetscMPIInt p = owner(colmap[oj[oi[i]]]);
    for (PetscInt e = oi[i] + 1; e < oi[i + 1] && p >= 0; ++e)
      if (owner(colmap[oj[e]]) != p) p = -1;
    target[i] = p;
    if (p >= 0) candidates.push_back(i);
  }
  // A candidate stays one while its on-process columns are candidates with the same target.
  const auto settle = [&] {
    for (bool changed = true; changed;) {
      changed = false;
      for (PetscInt i : candidates)
        if (target[i] >= 0)
          for (PetscInt e = ai[i]; e < ai[i + 1]; ++e)
            if (target[aj[e]] != target[i]) {
              target[i] = -1, changed = true;
              break;
            }
    }
  };
  settle();
  // Every rank's candidates (global rows, ascending): none whose off-process columns are candidates.
  const auto gather = [&](const std::vector<PetscInt> &mine, std::vector<PetscInt> *all) -> PetscErrorCode {
    PetscFunctionBeginUser;
    const PetscMPIInt count = static_cast<PetscMPIInt>(mine.size());
    std::vector<PetscMPIInt> counts(size), offsets(size + 1, 0);
    PetscCallMPI(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, ctx->comm));
    for (int r = 0; r < size; ++r) offsets[r + 1] = offsets[r] + counts[r];
    all->resize(offsets[size]);
    PetscCallMPI(MPI_Allgatherv(mine.data(), count, MPIU_INT, all->data(), counts.data(), offsets.data(), MPIU_INT, ctx->comm));
    PetscFunctionReturn(0);
  };
  std::vector<PetscInt> mine, all;
  for (PetscInt i : candidates)
    if (target[i] >= 0) mine.push_back(rowStart + i);
  PetscCall(gather(mine, &all));
  if (!all.empty()) {
    for (PetscInt i : candidates)
      if (target[i] >= 0)
        for (PetscInt e = oi[i]; e < oi[i + 1]; ++e)
          if (std::binary_search(all.begin(), all.end(), colmap[oj[e]])) {
            target[i] = -1;
            break;
          }
    settle();
    // The final adoptions as (global row, adopter) pairs, ascending in the row.
    mine.clear();
    for (PetscInt i : candidates)
      if (target[i] >= 0) mine.push_back(rowStart + i), mine.push_back(target[i]);
    PetscCall(gather(mine, &all));
    for (std::size_t k = 0; k < all.size(); k += 2) {
      if (all[k + 1] != rank) continue;
      const PetscMPIInt r = owner(all[k]);
      if (ctx->adoptedFrom.empty() || ctx->adoptedFrom.back() != r) {
        ctx->adoptedFrom.push_back(r);
        ctx->adoptedFromOffset.push_back(ctx->adoptedFromOffset.back());
      }
      ctx->adoptedGlobal.push_back(all[k]);
      ++ctx->adoptedFromOffset.back();
    }
    for (PetscMPIInt t = 0; t < size; ++t) {
      const std::size_t before = ctx->givenLocal.size();
      for (PetscInt i : candidates)
        if (target[i] == t) ctx->givenLocal.push_back(i);
      if (ctx->givenLocal.size() > before) ctx->givenTo.push_back(t), ctx->givenToOffset.push_back((PetscInt)ctx->givenLocal.size());
    }
  }
  // The given rows to their adopters: lengths and global columns, and values.
  const std::size_t nTo = ctx->givenTo.size();
  std::vector<std::vector<PetscInt>> patterns(nTo);
  std::vector<std::vector<double>> values(nTo);
  std::vector<MPI_Request> requests;
  if (nTo > 0) {
    const PetscScalar *av, *ov;
    PetscCall(MatSeqAIJGetArrayRead(Ad, &av));
    PetscCall(MatSeqAIJGetArrayRead(Ao, &ov));
    for (std::size_t t = 0; t < nTo; ++t) {
      std::vector<PetscInt> &pat = patterns[t];
      std::vector<double> &val = values[t];
      for (PetscInt k = ctx->givenToOffset[t]; k < ctx->givenToOffset[t + 1]; ++k) {
        const PetscInt i = ctx->givenLocal[k];
        pat.push_back(ai[i + 1] - ai[i] + oi[i + 1] - oi[i]);
      }
      for (PetscInt k = ctx->givenToOffset[t]; k < ctx->givenToOffset[t + 1]; ++k) {
        const PetscInt i = ctx->givenLocal[k];
        for (PetscInt e = ai[i]; e < ai[i + 1]; ++e) pat.push_back(rowStart + aj[e]), val.push_back(av[e]);
        for (PetscInt e = oi[i]; e < oi[i + 1]; ++e) pat.push_back(colmap[oj[e]]), val.push_back(ov[e]);
      }
      requests.emplace_back();
      PetscCallMPI(MPI_Isend(pat.data(), (PetscMPIInt)pat.size(), MPIU_INT, ctx->givenTo[t], kTagPattern, ctx->p2p, &requests.back()));
      requests.emplace_back();
      PetscCallMPI(MPI_Isend(val.data(), (PetscMPIInt)val.size(), MPIU_SCALAR, ctx->givenTo[t], kTagValues, ctx->p2p, &requests.back()));
    }
    PetscCall(MatSeqAIJRestoreArrayRead(Ao, &ov));
    PetscCall(MatSeqAIJRestoreArrayRead(Ad, &av));
  }
  std::vector<AdoptedRows> offered(ctx->adoptedFrom.size());
  for (std::size_t f = 0; f < ctx->adoptedFrom.size(); ++f) {
    const PetscMPIInt r = ctx->adoptedFrom[f];
    const PetscInt rows = ctx->adoptedFromOffset[f + 1] - ctx->adoptedFromOffset[f];
    MPI_Status status;
    PetscMPIInt count;
    PetscCallMPI(MPI_Probe(r, kTagPattern, ctx->p2p, &status));
    PetscCallMPI(MPI_Get_count(&status, MPIU_INT, &count));
    std::vector<PetscInt> pat(count);
    PetscCallMPI(MPI_Recv(pat.data(), count, MPIU_INT, r, kTagPattern, ctx->p2p, MPI_STATUS_IGNORE));
    PetscCheck(count >= rows, PETSC_COMM_SELF, PETSC_ERR_PLIB, "adopted rows' pattern too short");
    offered[f].length.assign(pat.begin(), pat.begin() + rows);
    offered[f].columns.assign(pat.begin() + rows, pat.end());
    offered[f].values.resize(count - rows);
    PetscCallMPI(MPI_Recv(offered[f].values.data(), count - (PetscMPIInt)rows, MPIU_SCALAR, r, kTagValues, ctx->p2p, MPI_STATUS_IGNORE));
  }
  // Accepted when every column of the offered rows on this rank is a row
  // with a nonzero diagonal whose off-process columns are all accepted rows:
  // then the adopted rows meet interior unknowns only (at acceleration level
  // a clamp's rows against the mass of its node: nonsingular). An owner's
  // rows are accepted or refused together (they may form one group).
  std::vector<char> accepted(ctx->adoptedFrom.size(), 1);
  if (!ctx->adoptedFrom.empty()) {
    const PetscScalar *av;
    PetscCall(MatSeqAIJGetArrayRead(Ad, &av));
    const auto hasDiagonal = [&](PetscInt j) { // only the few rows the offered rows touch
      for (PetscInt e = ai[j]; e < ai[j + 1]; ++e)
        if (aj[e] == j) return av[e] != 0.0;
      return false;
    };
    for (bool changed = true; changed;) {
      changed = false;
      std::vector<PetscInt> acceptedRows;
      for (std::size_t f = 0; f < ctx->adoptedFrom.size(); ++f)
        if (accepted[f])
          acceptedRows.insert(acceptedRows.end(), ctx->adoptedGlobal.begin() + ctx->adoptedFromOffset[f],
                              ctx->adoptedGlobal.begin() + ctx->adoptedFromOffset[f + 1]);
      std::sort(acceptedRows.begin(), acceptedRows.end());
      for (std::size_t f = 0; f < ctx->adoptedFrom.size(); ++f) {
        if (!accepted[f]) continue;
        for (PetscInt g : offered[f].columns) {
          if (g < rowStart || g >= rowStart + nLocal) continue; // the group's own rows
          const PetscInt j = g - rowStart;
          bool ok = hasDiagonal(j);
          for (PetscInt e = oi[j]; e < oi[j + 1] && ok; ++e) ok = std::binary_search(acceptedRows.begin(), acceptedRows.end(), colmap[oj[e]]);
          if (!ok) {
            accepted[f] = 0, changed = true;
            break;
          }
        }
      }
    }
    PetscCall(MatSeqAIJRestoreArrayRead(Ad, &av));
  }
  // The answers to the owners, and theirs to this rank's offers.
  std::vector<int> answers(ctx->adoptedFrom.size()), replies(nTo);
  for (std::size_t f = 0; f < ctx->adoptedFrom.size(); ++f) {
    answers[f] = accepted[f];
    requests.emplace_back();
    PetscCallMPI(MPI_Isend(&answers[f], 1, MPI_INT, ctx->adoptedFrom[f], kTagAnswer, ctx->p2p, &requests.back()));
  }
  for (std::size_t t = 0; t < nTo; ++t)
    PetscCallMPI(MPI_Recv(&replies[t], 1, MPI_INT, ctx->givenTo[t], kTagAnswer, ctx->p2p, MPI_STATUS_IGNORE));
  for (std::size_t t = 0; t < nTo; ++t)
    PetscCall(PetscInfo(nullptr, "Schur adoption: %" PetscInt_FMT " rows offered to rank %d, %s\n",
                        ctx->givenToOffset[t + 1] - ctx->givenToOffset[t], (int)ctx->givenTo[t], replies[t] ? "accepted" : "refused"));
  if (!requests.empty()) PetscCallMPI(MPI_Waitall((PetscMPIInt)requests.size(), requests.data(), MPI_STATUSES_IGNORE));
  // Keep the accepted ones only.
  {
    std::vector<PetscInt> global, offsets(1, 0);
    std::vector<PetscMPIInt> from;
    for (std::size_t f = 0; f < ctx->adoptedFrom.size(); ++f) {
      if (!accepted[f]) continue;
      global.insert(global.end(), ctx->adoptedGlobal.begin() + ctx->adoptedFromOffset[f], ctx->adoptedGlobal.begin() + ctx->adoptedFromOffset[f + 1]);
      from.push_back(ctx->adoptedFrom[f]), offsets.push_back((PetscInt)global.size());
      in->length.insert(in->length.end(), offered[f].length.begin(), offered[f].length.end());
      in->columns.insert(in->columns.end(), offered[f].columns.begin(), offered[f].columns.end());
      in->values.insert(in->values.end(), offered[f].values.begin(), offered[f].values.end());
    }
    ctx->adoptedGlobal = std::move(global), ctx->adoptedFrom = std::move(from), ctx->adoptedFromOffset = std::move(offsets);
    std::vector<PetscInt> local, toOffsets(1, 0);
    std::vector<PetscMPIInt> to;
    for (std::size_t t = 0; t < nTo; ++t) {
      if (!replies[t]) continue;
      local.insert(local.end(), ctx->givenLocal.begin() + ctx->givenToOffset[t], ctx->givenLocal.begin() + ctx->givenToOffset[t + 1]);
      to.push_back(ctx->givenTo[t]), toOffsets.push_back((PetscInt)local.size());
    }
    ctx->givenLocal = std::move(local), ctx->givenTo = std::move(to), ctx->givenToOffset = std::move(toOffsets);
  }
  PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &n, &oi, &oj, &done));
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &n, &ai, &aj, &done));
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

  AdoptedRows in;
  PetscCall(adoptRows(ctx, A, Ad, Ao, colmap, &in));
  const PetscInt nA = static_cast<PetscInt>(ctx->adoptedGlobal.size());
  std::unordered_map<PetscInt, PetscInt> adoptedIndex; // global row -> extended local row nLocal + k
  for (PetscInt k = 0; k < nA; ++k) adoptedIndex[ctx->adoptedGlobal[k]] = ctx->nLocal + k;
  std::vector<char> given(ctx->nLocal, 0);
  for (PetscInt i : ctx->givenLocal) given[i] = 1;

  // Interface rows: those with entries in the off-process block (other
  // than in adopted rows). The Jacobian's pattern is structurally symmetric
  // (each work item adds a full block), so these are also the rows other
  // ranks' rows couple to.
  // Rows with a zero diagonal (multipliers, massless slack coordinates at
  // acceleration level) join the interface too: left in the interior they
  // could make its block singular (a slack row whose multipliers are
  // interface rows has nothing else), and they are few. Adopted rows, zero
  // diagonal or not, are interior: they couple to this rank's interior
  // unknowns only (a clamp's multipliers with the clamped node: a
  // nonsingular saddle point that KLU pivots as on one rank). Rows given
  // to another rank are neither.
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
  const PetscInt *offRows = nullptr, *offColumns = nullptr;
  PetscInt offCount = 0;
  PetscBool offDone = PETSC_FALSE;
  std::vector<PetscInt> aoAdoptedPosition;
  if (Ao) {
    PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &offCount, &offRows, &offColumns, &offDone));
    PetscCheck(offDone && offCount == ctx->nLocal, ctx->comm, PETSC_ERR_PLIB, "off-process block without row pointers");
  }
  for (PetscInt i = 0; i < ctx->nLocal; ++i) {
    if (given[i]) continue;
    PetscInt offProcess = offRows ? offRows[i + 1] - offRows[i] : 0;
    if (nA > 0)
      for (PetscInt e = offRows[i]; e < offRows[i + 1]; ++e)
        if (adoptedIndex.count(colmap[offColumns[e]])) --offProcess, aoAdoptedPosition.push_back(e);
    (offProcess > 0 || d[i] == 0.0 ? ctx->interface : ctx->interior).push_back(i);
  }
  for (PetscInt k = 0; k < nA; ++k) ctx->interior.push_back(ctx->nLocal + k);
  if (Ao) PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &offCount, &offRows, &offColumns, &offDone));
  PetscCall(VecRestoreArrayRead(diagonal, &d));
  PetscCall(VecDestroy(&diagonal));
  // Values from outside Ad: this rank's entries in adopted columns, then the adopted rows.
  ctx->extra.clear();
  if (!aoAdoptedPosition.empty() || nA > 0) {
    const PetscScalar *ov;
    PetscCall(MatSeqAIJGetArrayRead(Ao, &ov));
    for (PetscInt e : aoAdoptedPosition) ctx->extra.push_back(ov[e]);
    PetscCall(MatSeqAIJRestoreArrayRead(Ao, &ov));
    ctx->extra.insert(ctx->extra.end(), in.values.begin(), in.values.end());
  }
  // What fixes the extended pattern, for the split check.
  std::vector<PetscInt> adoptedPattern(ctx->adoptedGlobal);
  adoptedPattern.push_back(-1);
  adoptedPattern.insert(adoptedPattern.end(), in.length.begin(), in.length.end());
  adoptedPattern.insert(adoptedPattern.end(), in.columns.begin(), in.columns.end());
  adoptedPattern.push_back(-1);
  adoptedPattern.insert(adoptedPattern.end(), aoAdoptedPosition.begin(), aoAdoptedPosition.end());
  adoptedPattern.push_back(static_cast<PetscInt>(ctx->givenLocal.size()));
  const bool samePattern = adoptedPattern == ctx->adoptedPattern;
  ctx->adoptedPattern = std::move(adoptedPattern);
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

  PetscCall(PetscInfo(pc, "interface Schur complement: %" PetscInt_FMT " unknowns in all, %d on this rank, %zu interior (%" PetscInt_FMT " adopted from other ranks, %zu given to others)\n",
                      ctx->nInterface, (int)nG, ctx->interior.size(), nA, ctx->givenLocal.size()));
  // Interior block, factored with KLU, and the blocks that couple it to this
  // rank's interface. The same operator with the same split (a Jacobian
  // refreshed in place) keeps the blocks and the symbolic factorization.
  PetscInt64 id;
  PetscCall(PetscObjectGetId((PetscObject)A, &id));
  const bool sameSplit = id == ctx->matrixId && ctx->interior == oldInterior && ctx->interface == oldInterface && samePattern;
  if (!sameSplit) PetscCall(ctx->destroy());
  const MatReuse reuse = sameSplit ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX;
  const PetscInt nI = static_cast<PetscInt>(ctx->interior.size());
  IS isI, isG;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nI, ctx->interior.data(), PETSC_USE_POINTER, &isI));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nG, ctx->interface.data(), PETSC_USE_POINTER, &isG));
  Mat *blocks[4] = {&ctx->AII, &ctx->AGI, &ctx->AIG, &ctx->AGG};
  if (reuse == MAT_INITIAL_MATRIX) {
    // With adopted rows (or entries in adopted columns) the blocks are cut
    // from Ad extended by them: rows and columns nLocal + k, entries whose
    // source index >= nnz(Ad) come from `extra`.
    Mat Aext = Ad;
    std::vector<PetscInt> extendedSource; // per entry of Aext: its source index
    std::vector<PetscInt> ei, ej;
    std::vector<PetscScalar> ev;
    const PetscInt *ai, *aj;
    PetscInt n;
    PetscBool done;
    PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &n, &ai, &aj, &done));
    PetscCheck(done && n == ctx->nLocal, PETSC_COMM_SELF, PETSC_ERR_PLIB, "diagonal block without row pointers");
    ctx->adNonzeros = ai[n];
    if (!ctx->extra.empty() || nA > 0) {
      const PetscInt nLocal = ctx->nLocal, nExt = nLocal + nA;
      const PetscScalar *av;
      PetscCall(MatSeqAIJGetArrayRead(Ad, &av));
      const PetscInt *oi = nullptr, *oj = nullptr;
      if (Ao) PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &n, &oi, &oj, &done));
      ei.assign(1, 0);
      std::size_t nextAo = 0; // into aoAdoptedPosition
      std::vector<std::pair<PetscInt, PetscInt>> row; // (column, source)
      for (PetscInt i = 0; i < nExt; ++i) {
        row.clear();
        if (i < nLocal) {
          for (PetscInt e = ai[i]; e < ai[i + 1]; ++e) row.emplace_back(aj[e], e);
          for (; nextAo < aoAdoptedPosition.size() && oi && aoAdoptedPosition[nextAo] < oi[i + 1]; ++nextAo)
            row.emplace_back(adoptedIndex.at(colmap[oj[aoAdoptedPosition[nextAo]]]), ctx->adNonzeros + (PetscInt)nextAo);
        } else {
          const PetscInt k = i - nLocal;
          PetscInt first = 0;
          for (PetscInt r = 0; r < k; ++r) first += in.length[r];
          for (PetscInt e = first; e < first + in.length[k]; ++e) {
            const PetscInt g = in.columns[e];
            PetscInt c;
            if (g >= ctx->rowStart && g < ctx->rowStart + nLocal) c = g - ctx->rowStart;
            else {
              const auto it = adoptedIndex.find(g);
              PetscCheck(it != adoptedIndex.end(), PETSC_COMM_SELF, PETSC_ERR_PLIB,
                         "adopted row %" PetscInt_FMT " couples to column %" PetscInt_FMT " of another rank", ctx->adoptedGlobal[k], g);
              c = it->second;
            }
            row.emplace_back(c, ctx->adNonzeros + (PetscInt)aoAdoptedPosition.size() + e);
          }
        }
        std::sort(row.begin(), row.end());
        for (const auto &[c, src] : row) {
          ej.push_back(c), extendedSource.push_back(src);
          ev.push_back(src < ctx->adNonzeros ? av[src] : ctx->extra[src - ctx->adNonzeros]);
        }
        ei.push_back((PetscInt)ej.size());
      }
      if (Ao) PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &n, &oi, &oj, &done));
      PetscCall(MatSeqAIJRestoreArrayRead(Ad, &av));
      PetscCall(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, nExt, nExt, ei.data(), ej.data(), ev.data(), &Aext));
    }
    PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &n, &ai, &aj, &done));
    PetscCall(MatCreateSubMatrix(Aext, isI, isI, reuse, &ctx->AII));
    PetscCall(MatCreateSubMatrix(Aext, isG, isI, reuse, &ctx->AGI));
    PetscCall(MatCreateSubMatrix(Aext, isI, isG, reuse, &ctx->AIG));
    PetscCall(MatCreateSubMatrix(Aext, isG, isG, reuse, &ctx->AGG));
    PetscCall(blockSources(Aext, ctx->interior, ctx->interior, *blocks[0], &ctx->sourceOf[0]));
    PetscCall(blockSources(Aext, ctx->interface, ctx->interior, *blocks[1], &ctx->sourceOf[1]));
    PetscCall(blockSources(Aext, ctx->interior, ctx->interface, *blocks[2], &ctx->sourceOf[2]));
    PetscCall(blockSources(Aext, ctx->interface, ctx->interface, *blocks[3], &ctx->sourceOf[3]));
    if (Aext != Ad) {
      for (auto &sources : ctx->sourceOf)
        for (PetscInt &e : sources) e = extendedSource[e];
      PetscCall(MatDestroy(&Aext));
    }
  } else {
    const PetscScalar *source;
    PetscCall(MatSeqAIJGetArrayRead(Ad, &source));
    const PetscInt adNonzeros = ctx->adNonzeros;
    const double *extra = ctx->extra.data() - adNonzeros;
    for (int b = 0; b < 4; ++b) {
      PetscScalar *target;
      PetscCall(MatSeqAIJGetArrayWrite(*blocks[b], &target));
      const std::vector<PetscInt> &from = ctx->sourceOf[b];
      if (ctx->extra.empty())
        for (std::size_t k = 0; k < from.size(); ++k) target[k] = source[from[k]];
      else
        for (std::size_t k = 0; k < from.size(); ++k) target[k] = from[k] < adNonzeros ? source[from[k]] : extra[from[k]];
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
        if (nA > 0 && adoptedIndex.count(colmap[cols[c]])) continue; // in AGI, from the extended rows
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
  // Adopted rows: their owners send b there, and get x back at the end.
  std::vector<MPI_Request> &requests = ctx->requests;
  requests.clear();
  const std::size_t nGiven = ctx->givenLocal.size(), nAdopted = ctx->adoptedGlobal.size();
  ctx->givenB.resize(nGiven), ctx->givenX.resize(nGiven), ctx->adoptedB.resize(nAdopted), ctx->adoptedX.resize(nAdopted);
  for (std::size_t k = 0; k < nGiven; ++k) ctx->givenB[k] = barr[ctx->givenLocal[k]];
  for (std::size_t t = 0; t < ctx->givenTo.size(); ++t) {
    const PetscInt from = ctx->givenToOffset[t], count = ctx->givenToOffset[t + 1] - from;
    requests.emplace_back();
    PetscCallMPI(MPI_Isend(ctx->givenB.data() + from, (PetscMPIInt)count, MPIU_SCALAR, ctx->givenTo[t], kTagB, ctx->p2p, &requests.back()));
    requests.emplace_back();
    PetscCallMPI(MPI_Irecv(ctx->givenX.data() + from, (PetscMPIInt)count, MPIU_SCALAR, ctx->givenTo[t], kTagX, ctx->p2p, &requests.back()));
  }
  if (nAdopted > 0) {
    std::vector<MPI_Request> receives(ctx->adoptedFrom.size());
    for (std::size_t f = 0; f < ctx->adoptedFrom.size(); ++f) {
      const PetscInt from = ctx->adoptedFromOffset[f], count = ctx->adoptedFromOffset[f + 1] - from;
      PetscCallMPI(MPI_Irecv(ctx->adoptedB.data() + from, (PetscMPIInt)count, MPIU_SCALAR, ctx->adoptedFrom[f], kTagB, ctx->p2p, &receives[f]));
    }
    PetscCallMPI(MPI_Waitall((PetscMPIInt)receives.size(), receives.data(), MPI_STATUSES_IGNORE));
  }
  // w = U^{-T} b_I(Q), all of it; then y = A_II^{-1} b_I at J only: the
  // back substitution from the end down to J's first column position.
  const PetscInt *gatherB = ctx->gatherB.data();
  if (nAdopted == 0) {
    for (PetscInt m = 0; m < nI; ++m) w[m] = barr[gatherB[m]];
  } else {
    const PetscInt nLocal = ctx->nLocal;
    const double *bAdopted = ctx->adoptedB.data() - nLocal;
    for (PetscInt m = 0; m < nI; ++m) w[m] = gatherB[m] < nLocal ? barr[gatherB[m]] : bAdopted[gatherB[m]];
  }
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
  if (nAdopted == 0) {
    for (PetscInt m = 0; m < nI; ++m) xarr[scatterX[m]] = w[m];
  } else {
    const PetscInt nLocal = ctx->nLocal;
    double *xAdopted = ctx->adoptedX.data() - nLocal;
    for (PetscInt m = 0; m < nI; ++m) (scatterX[m] < nLocal ? xarr : xAdopted)[scatterX[m]] = w[m];
    for (std::size_t f = 0; f < ctx->adoptedFrom.size(); ++f) {
      const PetscInt from = ctx->adoptedFromOffset[f], count = ctx->adoptedFromOffset[f + 1] - from;
      requests.emplace_back();
      PetscCallMPI(MPI_Isend(ctx->adoptedX.data() + from, (PetscMPIInt)count, MPIU_SCALAR, ctx->adoptedFrom[f], kTagX, ctx->p2p, &requests.back()));
    }
  }
  for (PetscInt k = 0; k < nG; ++k) xarr[ctx->interface[k]] = xMine[k];
  if (!requests.empty()) PetscCallMPI(MPI_Waitall((PetscMPIInt)requests.size(), requests.data(), MPI_STATUSES_IGNORE));
  for (std::size_t k = 0; k < nGiven; ++k) xarr[ctx->givenLocal[k]] = ctx->givenX[k];
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
  if (ctx->p2p != MPI_COMM_NULL) PetscCallMPI(MPI_Comm_free(&ctx->p2p));
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
  layout->adoptedRows = ctx->adoptedGlobal;
  layout->given = static_cast<PetscInt>(ctx->givenLocal.size());
  layout->interfaceRows.clear();
  for (PetscInt i : ctx->interface) layout->interfaceRows.push_back(ctx->rowStart + i);
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
