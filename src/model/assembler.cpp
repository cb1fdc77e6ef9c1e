#include "boomdyn/assembler.hpp"

#include "boomdyn/lanes.hpp"
#include "boomdyn/log_events.hpp"
#include "boomdyn/partition.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace boomdyn {

namespace {

using lanes::Lanes4;
using lanes::load;
using lanes::store;

} // namespace

inline void Assembler::addResidual(std::size_t k, double *r, double *f) const
{
  // f[local] += r entry by entry, and r cleared for the next item (see
  // evaluate()). f is not zeroed beforehand: the first item to touch an
  // entry (first_) stores 0.0 + r, which is bit for bit what adding r to
  // the zero of a VecSet gives; the others add. An item on consecutive
  // entries goes four at a time (the same sums: each entry of f receives
  // its items' values in the items' order).
  const int begin = itemStart_[k], n = itemStart_[k + 1] - begin;
  const PetscInt *local = itemLocal_.data() + begin;
  const char *first = first_.data() + begin;
  int i = 0;
  if (plain_[k]) {
    double *fk = f + local[0];
    for (; i + 4 <= n; i += 4) {
      std::uint32_t flags;
      std::memcpy(&flags, first + i, sizeof flags);
      if (flags == 0) store(fk + i, load(fk + i) + load(r + i));
      else if (flags == 0x01010101u) store(fk + i, Lanes4{} + load(r + i));
      else
        for (int d = i; d < i + 4; ++d) fk[d] = (first[d] ? 0.0 : fk[d]) + r[d];
      store(r + i, Lanes4{});
    }
  }
  for (; i < n; ++i) {
    f[local[i]] = (first[i] ? 0.0 : f[local[i]]) + r[i];
    r[i] = 0.0;
  }
}

PetscErrorCode Assembler::setUp(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  comm_ = comm;
  PetscCall(registerLogEvents());
  PetscCall(VecCreate(comm, xTemplate_.address()));
  PetscCall(VecSetSizes(xTemplate_, PETSC_DECIDE, model_.size()));
  PetscCall(VecSetFromOptions(xTemplate_));
  PetscCall(VecSetUp(xTemplate_));
  // Which rank evaluates which work item: by default the owner of the item's
  // first unknown (the contiguous split of each boom); -boom_partition metis:
  // a METIS k-way partition of the work-item graph, computed identically on
  // every rank. Rows stay in contiguous blocks either way; entries an item
  // computes for rows of another rank travel with MatSetValuesCOO and the
  // reverse scatter.
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  char method[32] = "contiguous";
  PetscCall(PetscOptionsGetString(nullptr, "boom_", "-partition", method, sizeof method, nullptr));
  const std::string m = method;
  PetscCheck(m == "contiguous" || m == "metis", comm, PETSC_ERR_USER_INPUT,
             "-boom_partition must be 'contiguous' or 'metis', got '%s'", method);
  itemRank_.clear();
  if (m == "metis" && size > 1) itemRank_ = metisPartition(model_, size);
  PetscCall(buildPattern());
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::rebuildPattern()
{
  PetscFunctionBeginUser;
  // Sliding joints moved to other elements: new dof lists, owners, scatter and COO pattern.
  scatter_.reset();
  xLocal_.reset();
  fLocal_.reset();
  PetscCall(buildPattern());
  ++patternVersion_;
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::buildPattern()
{
  PetscInt lo, hi;
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(xTemplate_, &lo, &hi));
  // Items whose first coordinate this rank owns (contiguous coordinate
  // numbering per body makes this a contiguous split of each boom's
  // elements), or the items the METIS partition gives this rank.
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  std::vector<PetscInt> coords, rows;
  std::size_t index = 0;
  std::vector<std::vector<PetscInt>> dofLists;
  items_.clear();
  itemCoords_.clear();
  itemLocal_.clear();
  cooI_.clear();
  cooJ_.clear();
  for (const auto &item : model_.items()) {
    item->coordinates(coords);
    PetscCheck(!coords.empty(), comm_, PETSC_ERR_PLIB, "work item %s touches no coordinate", item->name().c_str());
    const bool mine = itemRank_.empty() ? coords[0] >= lo && coords[0] < hi : itemRank_[index] == rank;
    ++index;
    if (!mine) continue;
    item->multiplierRows(rows);
    items_.push_back(item.get());
    itemCoords_.push_back(static_cast<int>(coords.size()));
    coords.insert(coords.end(), rows.begin(), rows.end());
    dofLists.push_back(coords);
  }

  // Local numbering of every global index this rank's items touch.
  std::vector<PetscInt> needed;
  for (const auto &d : dofLists) needed.insert(needed.end(), d.begin(), d.end());
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  std::unordered_map<PetscInt, PetscInt> localOf;
  for (std::size_t i = 0; i < needed.size(); ++i) localOf[needed[i]] = static_cast<PetscInt>(i);

  itemStart_.assign(1, 0);
  cooStart_.assign(1, 0);
  std::size_t maxN = 0;
  for (const auto &d : dofLists) {
    for (PetscInt g : d) itemLocal_.push_back(localOf[g]);
    itemStart_.push_back(static_cast<int>(itemLocal_.size()));
    for (PetscInt gi : d)
      for (PetscInt gj : d) {
        cooI_.push_back(gi);
        cooJ_.push_back(gj);
      }
    cooStart_.push_back(static_cast<PetscCount>(cooI_.size()));
    maxN = std::max(maxN, d.size());
  }
  cooV_.assign(cooI_.size(), 0.0);

  const PetscInt nloc = static_cast<PetscInt>(needed.size());
  IS is;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nloc, needed.data(), PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, nloc, xLocal_.address()));
  PetscCall(VecDuplicate(xLocal_, fLocal_.address()));
  PetscCall(VecScatterCreate(xTemplate_, is, xLocal_, nullptr, scatter_.address()));
  PetscCall(ISDestroy(&is));
  // One rank (or ranks whose items all touch only their own unknowns): the
  // local vector is the owned part of x in the same order, and the scatters
  // are copies that can be skipped (x and F are read and written in place).
  // Decided by all ranks together: the scatter is collective (its first use
  // sets up a PetscSF, whose two-sided setup every rank enters), so one rank
  // skipping it while another needs it hung the run (a cantilever clamped
  // at its end on 2 ranks: the last rank owns the clamp's coordinates and
  // multipliers, so its items touch only its own rows).
  const int mine = nloc == hi - lo && (nloc == 0 || (needed.front() == lo && needed.back() == hi - 1)) ? 1 : 0;
  int everywhere = 0;
  PetscCallMPI(MPI_Allreduce(&mine, &everywhere, 1, MPI_INT, MPI_MIN, comm_));
  inPlace_ = everywhere == 1;
  qc_.assign(nloc, 0.0), vc_.assign(nloc, 0.0), ac_.assign(nloc, 0.0);
  offsetZero_[0] = offsetZero_[1] = offsetZero_[2] = true;
  firstOrder_.assign(nloc, 0);
  for (PetscInt g : model_.firstOrderCoordinates()) {
    const auto it = localOf.find(g);
    if (it != localOf.end()) firstOrder_[it->second] = 1;
  }
  // q, v, a: one block per pencil pass (evaluatePencil) or per item of a
  // residual batch; the single gathers use the first.
  slot_ = maxN;
  const std::size_t blocks = std::max(kPencilPasses, kResidualBatch);
  for (auto *b : {&bq_, &bv_, &ba_, &bl_, &br_}) b->assign(blocks * slot_, 0.0);
  // The first item entry (in the items' order) that touches each local
  // entry, and the entries no item touches (addResidual, evaluate()).
  first_.assign(itemLocal_.size(), 0);
  std::vector<char> touched(nloc, 0);
  for (std::size_t i = 0; i < itemLocal_.size(); ++i)
    if (!touched[itemLocal_[i]]) touched[itemLocal_[i]] = 1, first_[i] = 1;
  untouched_.clear();
  for (PetscInt i = 0; i < nloc; ++i)
    if (!touched[i]) untouched_.push_back(i);
  // Items whose local entries are consecutive and none a first-order state (gather()'s plain path).
  plain_.assign(items_.size(), 0);
  for (std::size_t k = 0; k < items_.size(); ++k) {
    bool plain = true;
    for (int i = itemStart_[k]; i < itemStart_[k + 1]; ++i)
      plain = plain && itemLocal_[i] == itemLocal_[itemStart_[k]] + (i - itemStart_[k]) && !firstOrder_[itemLocal_[i]];
    plain_[k] = plain;
  }
  // Residual batches: runs of consecutive items with the same batch key, cut
  // into groups of at most kResidualBatch (the order of the items, and so
  // of the sums into F, stays that of the model).
  batch_.assign(items_.size(), 1);
  for (std::size_t k = 0; k < items_.size();) {
    const void *key = items_[k]->residualBatchKey();
    std::size_t m = 1;
    while (key && m < static_cast<std::size_t>(kResidualBatch) && k + m < items_.size() &&
           items_[k + m]->residualBatchKey() == key)
      ++m;
    batch_[k] = static_cast<unsigned char>(m);
    k += m;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::createVector(Vec *x) const
{
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(xTemplate_, x));
  PetscCall(VecSet(*x, 0.0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::createMatrix(Mat *J) const
{
  PetscInt nlocal;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(xTemplate_, &nlocal));
  PetscCall(MatCreate(comm_, J));
  PetscCall(MatSetSizes(*J, nlocal, nlocal, model_.size(), model_.size()));
  PetscCall(MatSetType(*J, MATAIJ));
  // MatSetPreallocationCOO may reorder or mark the index arrays it is given:
  // hand it copies so that every matrix built here gets the same pattern in
  // the order of cooV_ (a shared array gave the second matrix scrambled values).
  std::vector<PetscInt> I(cooI_), Jc(cooJ_);
  PetscCall(MatSetPreallocationCOO(*J, static_cast<PetscCount>(I.size()), I.data(), Jc.data()));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::setOffsets(Vec qc, Vec vc, Vec ac)
{
  PetscFunctionBeginUser;
  std::vector<double> *dst[3] = {&qc_, &vc_, &ac_};
  Vec src[3] = {qc, vc, ac};
  for (int k = 0; k < 3; ++k) {
    if (!src[k]) {
      // Zero offsets are filled once, not at every solve (the steps pass
      // qc = 0 each time: a pass over a vector of the whole state).
      if (!offsetZero_[k]) std::fill(dst[k]->begin(), dst[k]->end(), 0.0);
      offsetZero_[k] = true;
      continue;
    }
    offsetZero_[k] = false;
    const PetscScalar *arr;
    Vec local = inPlace_ ? src[k] : xLocal_.get();
    if (!inPlace_) {
      PetscCall(VecScatterBegin(scatter_, src[k], xLocal_, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterEnd(scatter_, src[k], xLocal_, INSERT_VALUES, SCATTER_FORWARD));
    }
    PetscCall(VecGetArrayRead(local, &arr));
    std::copy(arr, arr + dst[k]->size(), dst[k]->begin());
    PetscCall(VecRestoreArrayRead(local, &arr));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::beginLocal(const AssemblyContext &ctx, Vec x)
{
  PetscFunctionBeginUser;
  localSource_ = inPlace_ ? x : xLocal_.get();
  if (!inPlace_) {
    PetscCall(VecScatterBegin(scatter_, x, xLocal_, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(scatter_, x, xLocal_, INSERT_VALUES, SCATTER_FORWARD));
  }
  PetscCall(VecGetArrayRead(localSource_, &xl_));
  kin_ = ctx.kin;
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::endLocal()
{
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArrayRead(localSource_, &xl_));
  xl_ = nullptr;
  localSource_ = nullptr;
  PetscFunctionReturn(0);
}

inline void Assembler::gather(std::size_t k, ItemValues &vals, int slot)
{
  // The affine map q = qc + cQ x, v = vc + cV x (cZ for first-order
  // states), a = ac + cA x, entry by entry for this item's unknowns only
  // (the same operations as a map of the whole local vector, without
  // writing and re-reading four arrays of its size); multipliers as given.
  const int begin = itemStart_[k], n = itemStart_[k + 1] - begin, nc = itemCoords_[k];
  const Kinematics &c = kin_;
  const std::size_t o = slot * slot_;
  double *bq = bq_.data() + o, *bv = bv_.data() + o, *ba = ba_.data() + o, *bl = bl_.data() + o;
  if (plain_[k]) {
    // Consecutive local entries, none a first-order state (a beam
    // element's 8 coordinates): the same operations as below on contiguous
    // slices, which the compiler vectorizes (no index loads, no select);
    // the indexed loop was a fifth of a residual's instructions once the
    // element kernel was batched.
    const PetscInt l0 = itemLocal_[begin];
    const double *x = xl_ + l0, *qc = qc_.data() + l0, *vc = vc_.data() + l0, *ac = ac_.data() + l0;
    const double cQ = c.cQ, cV = c.cV, cA = c.cA;
    // Four entries at a time in explicit vectors (GCC did not vectorize the
    // loop: the buffers might alias the sources); lane-wise the same
    // multiply and add.
    int i = 0;
    for (; i + 4 <= n; i += 4) {
      const Lanes4 xi = load(x + i);
      store(bq + i, load(qc + i) + cQ * xi);
      store(bv + i, load(vc + i) + cV * xi);
      store(ba + i, load(ac + i) + cA * xi);
      store(bl + i, xi);
    }
    for (; i < n; ++i) {
      bq[i] = qc[i] + cQ * x[i];
      bv[i] = vc[i] + cV * x[i];
      ba[i] = ac[i] + cA * x[i];
      bl[i] = x[i];
    }
  } else {
    for (int i = 0; i < n; ++i) {
      const PetscInt li = itemLocal_[begin + i];
      const double x = xl_[li];
      bq[i] = qc_[li] + c.cQ * x;
      bv[i] = vc_[li] + (firstOrder_[li] ? c.cZ : c.cV) * x;
      ba[i] = ac_[li] + c.cA * x;
      bl[i] = x;
    }
  }
  vals.q = bq;
  vals.v = bv;
  vals.a = ba;
  vals.lambda = bl + nc;
}

PetscErrorCode Assembler::evaluate(const AssemblyContext &context, Vec x, Vec F, Mat J)
{
  AssemblyContext ctx = context;
  ctx.residualWanted = F != nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().assembly, 0, 0, 0, 0));
  PetscCall(beginLocal(ctx, x));
  // The residual accumulates in F itself when the local vector is x's own
  // part (one rank), else in fLocal_, added into F by the reverse scatter.
  Vec fTarget = F ? (inPlace_ ? F : fLocal_.get()) : nullptr;
  PetscScalar *fl = nullptr;
  if (F) {
    // No VecSet: the items' first contributions store (addResidual); only
    // entries no item touches are zeroed here.
    PetscCall(VecGetArray(fTarget, &fl));
    for (PetscInt i : untouched_) fl[i] = 0.0;
  }
  ItemValues vals;
  // Items add into a zeroed residual block. With F wanted, br_ is zeroed
  // once here and then stays zero between items (the scatter below clears
  // what it has read: a fill of 8 entries per item was a memset call, 4 % of
  // a residual's instructions on the long boom); without F, per item.
  double *br = br_.data();
  std::fill(br_.begin(), br_.end(), 0.0);
  for (std::size_t k = 0; k < items_.size(); ++k) {
    const int begin = itemStart_[k], n = itemStart_[k + 1] - begin;
    if (fl && !J && batch_[k] > 1) {
      // Residuals only: the batch's items in one call (a beam's elements
      // share a SIMD kernel), each in its own block of the buffers; their
      // residuals are added into F in the items' order, as one by one.
      const int m = batch_[k];
      ItemValues in[kResidualBatch];
      double *res[kResidualBatch];
      for (int j = 0; j < m; ++j) gather(k + j, in[j], j), res[j] = br + j * slot_;
      items_[k]->evaluateResiduals(ctx, items_.data() + k, in, res, m);
      for (int j = 0; j < m; ++j) addResidual(k + j, res[j], fl);
      k += m - 1;
      continue;
    }
    gather(k, vals);
    if (!fl) std::fill(br, br + n, 0.0);
    // The item's Jacobian block goes straight into its slice of the COO values.
    double *Jk = J ? cooV_.data() + cooStart_[k] : nullptr;
    if (Jk) std::fill(Jk, Jk + n * n, 0.0);
    items_[k]->evaluate(ctx, vals, br, Jk);
    if (fl) addResidual(k, br, fl);
  }
  PetscCall(endLocal());
  if (F) {
    PetscCall(VecRestoreArray(fTarget, &fl));
    if (!inPlace_) {
      PetscCall(VecSet(F, 0.0));
      PetscCall(VecScatterBegin(scatter_, fLocal_, F, ADD_VALUES, SCATTER_REVERSE));
      PetscCall(VecScatterEnd(scatter_, fLocal_, F, ADD_VALUES, SCATTER_REVERSE));
    }
  }
  if (J) PetscCall(MatSetValuesCOO(J, cooV_.data(), INSERT_VALUES));
  PetscCall(PetscLogEventEnd(logEvents().assembly, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::evaluatePencil(const AssemblyContext &context, Vec x, Mat A, Mat B, Mat D)
{
  // The three passes the eigen-analysis made before (docs/model.md §5), as
  // maps q = qc + cQ x, v = vc + cV x (cZ x for first-order states),
  // a = ac + cA x with the same constants and the same floating-point
  // operations, so that every item sees bitwise the values it saw then:
  //   A: qc = vc = ac = 0, cQ = 1, cV = cZ = cA = 0, constraint blocks as ctx;
  //   B: qc = x, vc = ac = 0, cA = 1, cQ = cV = cZ = 0, no constraint blocks;
  //   D: qc = x, vc = -x (0 for first-order states), ac = 0, cV = 1,
  //      cQ = cZ = cA = 0, no constraint blocks.
  // One pass over the items: each item's values of the three maps are
  // gathered together and the item fills its three blocks in one call
  // (WorkItem::evaluatePencil: the three evaluate() calls unless the item
  // shares work between them, bitwise to the same blocks).
  struct Pass {
    AssemblyContext ctx;
    Mat J;
    std::vector<PetscScalar> values;
  };
  Pass passes[kPencilPasses] = {{context, A, {}}, {context, B, {}}, {context, D, {}}};
  passes[0].ctx.kin = {1.0, 0.0, 0.0, 0.0};
  passes[1].ctx.kin = {0.0, 0.0, 1.0, 0.0};
  passes[2].ctx.kin = {0.0, 1.0, 0.0, 0.0};
  passes[1].ctx.constraintBlocks = passes[2].ctx.constraintBlocks = false;
  for (Pass &p : passes) {
    p.ctx.residualWanted = false;
    p.ctx.pencil = true;
    if (p.J) p.values.assign(cooV_.size(), 0.0);
  }
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().assembly, 0, 0, 0, 0));
  PetscCall(beginLocal(passes[0].ctx, x));
  // Per pass its own q, v, a arrays (bq_, bv_, ba_ hold kPencilPasses
  // blocks of the largest item's size: pencil buffers of setUp).
  const std::size_t stride = slot_;
  PencilPass item[kPencilPasses];
  for (int pass = 0; pass < kPencilPasses; ++pass) {
    item[pass].ctx = passes[pass].ctx;
    item[pass].in.q = bq_.data() + pass * stride;
    item[pass].in.v = bv_.data() + pass * stride;
    item[pass].in.a = ba_.data() + pass * stride;
  }
  for (std::size_t k = 0; k < items_.size(); ++k) {
    const int begin = itemStart_[k], n = itemStart_[k + 1] - begin, nc = itemCoords_[k];
    for (int i = 0; i < n; ++i) bl_[i] = xl_[itemLocal_[begin + i]];
    for (int pass = 0; pass < kPencilPasses; ++pass) {
      Pass &p = passes[pass];
      item[pass].J = p.J ? p.values.data() + cooStart_[k] : nullptr;
      item[pass].in.lambda = bl_.data() + nc;
      if (!p.J) continue;
      const Kinematics &c = p.ctx.kin;
      double *bq = bq_.data() + pass * stride, *bv = bv_.data() + pass * stride, *ba = ba_.data() + pass * stride;
      for (int i = 0; i < n; ++i) {
        const PetscInt li = itemLocal_[begin + i];
        const double xi = bl_[i], zero = 0.0;
        const double qc = pass == 0 ? zero : xi, vc = pass == 2 && !firstOrder_[li] ? -xi : zero;
        bq[i] = qc + c.cQ * xi;
        bv[i] = vc + (firstOrder_[li] ? c.cZ : c.cV) * xi;
        ba[i] = zero + c.cA * xi;
      }
    }
    items_[k]->evaluatePencil(item, n, br_.data());
  }
  PetscCall(endLocal());
  for (Pass &p : passes)
    if (p.J) PetscCall(MatSetValuesCOO(p.J, p.values.data(), INSERT_VALUES));
  PetscCall(setOffsets(x, nullptr, nullptr));
  PetscCall(PetscLogEventEnd(logEvents().assembly, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::diagnostics(const AssemblyContext &ctx, Vec x, EnergyParts *energy, PetscReal *maxViolation,
                                      DampingForces *forces)
{
  PetscFunctionBeginUser;
  PetscCall(beginLocal(ctx, x));
  EnergyParts e;
  double viol = 0;
  ItemValues vals;
  if (forces) startDampingForces(forces);
  for (std::size_t k = 0; k < items_.size(); ++k) {
    gather(k, vals);
    if (!forces) items_[k]->energy(ctx, vals, e);
    else if (items_[k]->energyAndDampingForce(ctx, vals, e, forces->f.data() + forces->used))
      takeDampingForce(k, forces);
    viol = std::max(viol, items_[k]->constraintViolation(ctx, vals));
  }
  if (forces) forces->f.resize(forces->used);
  PetscCall(endLocal());
  double sums[7] = {e.kinetic, e.strain, e.potential, e.inputPower, e.roundoff, e.dissipation, e.inputPowerJump},
         global[7];
  PetscCallMPI(MPI_Allreduce(sums, global, 7, MPI_DOUBLE, MPI_SUM, comm_));
  if (energy) {
    energy->kinetic = global[0], energy->strain = global[1], energy->potential = global[2];
    energy->inputPower = global[3], energy->roundoff = global[4], energy->dissipation = global[5];
    energy->inputPowerJump = global[6];
  }
  double gviol;
  PetscCallMPI(MPI_Allreduce(&viol, &gviol, 1, MPI_DOUBLE, MPI_MAX, comm_));
  if (maxViolation) *maxViolation = gviol;
  PetscFunctionReturn(0);
}

// The force array is sized for every item's coordinates once per pass (a
// resize per item was a call into the vector's growth path for each of
// them), filled by the items with damping forces and cut to what they used.
void Assembler::startDampingForces(DampingForces *forces) const
{
  forces->items.clear(), forces->first.clear();
  forces->used = 0;
  std::size_t total = 0;
  for (int n : itemCoords_) total += static_cast<std::size_t>(n);
  forces->f.resize(total);
}

void Assembler::addDampingForce(std::size_t k, const ItemValues &vals, DampingForces *forces) const
{
  if (items_[k]->dampingForce(vals, forces->f.data() + forces->used)) takeDampingForce(k, forces);
}

// Item k has written its damping forces at forces->f[used]: record them.
void Assembler::takeDampingForce(std::size_t k, DampingForces *forces) const
{
  forces->items.push_back(k);
  forces->first.push_back(static_cast<int>(forces->used));
  forces->used += static_cast<std::size_t>(itemCoords_[k]);
}

PetscErrorCode Assembler::dampingForces(Vec q, Vec v, DampingForces *forces)
{
  PetscFunctionBeginUser;
  // q from x itself, v through the offsets.
  AssemblyContext ctx;
  ctx.kin = {1.0, 0.0, 0.0};
  PetscCall(setOffsets(nullptr, v, nullptr));
  PetscCall(beginLocal(ctx, q));
  startDampingForces(forces);
  ItemValues vals;
  for (std::size_t k = 0; k < items_.size(); ++k) {
    gather(k, vals);
    addDampingForce(k, vals, forces);
  }
  forces->f.resize(forces->used);
  PetscCall(endLocal());
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::dampingWork(const DampingForces *const forces[], int count, Vec dq, PetscReal work[])
{
  PetscFunctionBeginUser;
  for (int k = 1; k < count; ++k)
    if (forces[k]->items != forces[0]->items || forces[k]->first != forces[0]->first) {
      // Not the same items (a contact point changed element in between): one pass each.
      for (int j = 0; j < count; ++j) PetscCall(dampingWork(&forces[j], 1, dq, &work[j]));
      PetscFunctionReturn(0);
    }
  // The increment's entries are read straight from the local values of dq
  // (a gather with q = 0 + 1 dq gives the same numbers, and the v and a it
  // would also form are not used); the offsets are left as they are.
  AssemblyContext ctx;
  PetscCall(beginLocal(ctx, dq));
  std::vector<double> local(count, 0.0);
  const DampingForces &layout = *forces[0];
  for (std::size_t i = 0; i < layout.items.size(); ++i) {
    const std::size_t k = layout.items[i];
    const PetscInt *li = itemLocal_.data() + itemStart_[k];
    for (int s = 0; s < count; ++s) {
      const double *f = forces[s]->f.data() + layout.first[i];
      double itemWork = 0; // per item, then summed: the order of the sums before
      for (int j = 0; j < itemCoords_[k]; ++j) itemWork += xl_[li[j]] * f[j];
      local[s] += itemWork;
    }
  }
  PetscCall(endLocal());
  PetscCallMPI(MPI_Allreduce(local.data(), work, count, MPI_DOUBLE, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::characteristicScales(Vec x, PetscReal *mass, PetscReal *stiffness)
{
  PetscFunctionBeginUser;
  AssemblyContext ctx;
  PetscCall(beginLocal(ctx, x));
  double sums[3] = {0, 0, 0}, global[3];
  int count = 0;
  ItemValues vals;
  for (std::size_t k = 0; k < items_.size(); ++k) {
    gather(k, vals);
    items_[k]->scales(vals, sums[0], sums[1], count);
  }
  PetscCall(endLocal());
  sums[2] = count;
  PetscCallMPI(MPI_Allreduce(sums, global, 3, MPI_DOUBLE, MPI_SUM, comm_));
  const double n = global[2] > 0 ? global[2] : 1.0;
  *mass = global[0] / n;
  *stiffness = global[1] / n;
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::coordinateRange(PetscInt *begin, PetscInt *end) const
{
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(xTemplate_, begin, end));
  *begin = std::min(*begin, model_.numCoordinates());
  *end = std::min(*end, model_.numCoordinates());
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::initialState(Vec x) const
{
  PetscInt lo, hi;
  PetscScalar *a;
  PetscFunctionBeginUser;
  const std::vector<double> q0 = model_.initialCoordinates();
  PetscCall(VecSet(x, 0.0));
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  PetscCall(VecGetArray(x, &a));
  for (PetscInt i = lo; i < std::min<PetscInt>(hi, model_.numCoordinates()); ++i) a[i - lo] = q0[i];
  PetscCall(VecRestoreArray(x, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::initialVelocity(Vec v) const
{
  PetscInt lo, hi;
  PetscScalar *a;
  PetscFunctionBeginUser;
  const std::vector<double> v0 = model_.initialVelocities();
  PetscCall(VecSet(v, 0.0));
  PetscCall(VecGetOwnershipRange(v, &lo, &hi));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = lo; i < std::min<PetscInt>(hi, model_.numCoordinates()); ++i) a[i - lo] = v0[i];
  PetscCall(VecRestoreArray(v, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::copyMultipliers(Vec src, Vec dst, PetscReal scale) const
{
  PetscInt lo, hi;
  const PetscScalar *s;
  PetscScalar *d;
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(src, &lo, &hi));
  PetscCall(VecGetArrayRead(src, &s));
  PetscCall(VecGetArray(dst, &d));
  for (PetscInt i = std::max(lo, model_.numCoordinates()); i < hi; ++i) d[i - lo] = scale * s[i - lo];
  PetscCall(VecRestoreArray(dst, &d));
  PetscCall(VecRestoreArrayRead(src, &s));
  PetscFunctionReturn(0);
}

} // namespace boomdyn

namespace boomdyn {

PetscErrorCode Assembler::modeEnergy(const AssemblyContext &context, Vec x, Vec shape, ModeEnergy *out)
{
  PetscFunctionBeginUser;
  // The shape's local values through the offsets (qc_), the state's through
  // beginLocal; each item gets the stiffness pass's values of the pencil
  // (q = x, v = a = 0, its multipliers) and the shape on its coordinates.
  PetscCall(setOffsets(shape, nullptr, nullptr));
  PencilPass pass;
  pass.ctx = context;
  pass.ctx.kin = {1.0, 0.0, 0.0, 0.0};
  pass.ctx.residualWanted = false;
  pass.ctx.pencil = true;
  PetscCall(beginLocal(pass.ctx, x));
  ModeEnergy local;
  std::vector<double> s(slot_), zeros(slot_, 0.0), block(slot_ * slot_);
  pass.in.q = bq_.data();
  pass.in.v = zeros.data();
  pass.in.a = zeros.data();
  for (std::size_t k = 0; k < items_.size(); ++k) {
    const int begin = itemStart_[k], n = itemStart_[k + 1] - begin, nc = itemCoords_[k];
    for (int i = 0; i < n; ++i) {
      const PetscInt li = itemLocal_[begin + i];
      bq_[i] = xl_[li];
      bl_[i] = xl_[li];
      s[i] = i < nc ? qc_[li] : 0.0;
    }
    pass.in.lambda = bl_.data() + nc;
    std::fill(block.begin(), block.begin() + n * n, 0.0);
    pass.J = block.data();
    items_[k]->modeEnergy(pass, n, s.data(), br_.data(), local);
  }
  PetscCall(endLocal());
  PetscCall(setOffsets(nullptr, nullptr, nullptr));
  PetscCallMPI(MPI_Allreduce(local.kind, out->kind, kModeEnergyKinds, MPI_DOUBLE, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
