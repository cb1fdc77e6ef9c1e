#include "boomdyn/beam_element_item.hpp"

#include "boomdyn/lanes.hpp"

#include <cmath>
#include <cstring>
#include <limits>

namespace boomdyn {

BeamElementItem::BeamElementItem(const AncfBeam &beam, int element, std::shared_ptr<const ancf::Mat8> mass,
                                 const Vec2 &gravity)
  : beam_(&beam), element_(element), mass_(std::move(mass)),
    gravity_(ancf::gravityForce(beam.section().rhoA, beam.elementLength(), gravity))
{
  // The consistent mass of the cable element is m ⊗ I2 (ancf::massMatrix):
  // x and y rows couple only to their own direction.
  const ancf::Mat8 &M = *mass_;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      kroneckerMass_ = kroneckerMass_ && (i % 2 == j % 2 ? M(i, j) == M(i - i % 2, j - j % 2) : M(i, j) == 0.0);
}

void BeamElementItem::inertiaAndForces(const double *a, const ancf::Vec8 &f, double loadFactor, double *residual) const
{
  Eigen::Map<ancf::Vec8> r(residual);
  if (!kroneckerMass_) {
    r = (*mass_) * Eigen::Map<const ancf::Vec8>(a) + f - loadFactor * gravity_;
    return;
  }
  // M a with M = m ⊗ I2: the 32 nonzero products of the 64, summed per row
  // in column order from zero as Eigen's matrix-vector product does (the
  // zero products it adds change no sum), so r is bit-identical to the
  // general expression above (test BeamElementItem.KroneckerMassProductIsBitIdentical);
  // half the multiplications, and no call of Eigen's product kernel, on
  // every element of every residual.
  // Both directions of a node at once (one SSE2 pair: x and y rows share m_ik).
  const ancf::Mat8 &M = *mass_;
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector2d s = Eigen::Vector2d::Zero();
    for (int k = 0; k < 4; ++k) s += M(2 * i, 2 * k) * Eigen::Map<const Eigen::Vector2d>(a + 2 * k);
    Eigen::Map<Eigen::Vector2d>(residual + 2 * i) = (s + f.segment<2>(2 * i)) - loadFactor * gravity_.segment<2>(2 * i);
  }
}

ancf::Vec8 BeamElementItem::massTimes(const double *v) const
{
  if (!kroneckerMass_) return (*mass_) * Eigen::Map<const ancf::Vec8>(v);
  // M v with M = m ⊗ I2 as in inertiaAndForces: the nonzero products summed
  // per row in column order from zero, bit-identical to Eigen's product
  // (the kinetic energy of every element after every step went through
  // Eigen's general matrix-vector kernel, 8 % of the diagnostics).
  const ancf::Mat8 &M = *mass_;
  ancf::Vec8 out;
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector2d s = Eigen::Vector2d::Zero();
    for (int k = 0; k < 4; ++k) s += M(2 * i, 2 * k) * Eigen::Map<const Eigen::Vector2d>(v + 2 * k);
    out.segment<2>(2 * i) = s;
  }
  return out;
}

std::string BeamElementItem::name() const { return beam_->name() + ".element" + std::to_string(element_); }

void BeamElementItem::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.resize(8);
  for (int k = 0; k < 8; ++k) dofs[k] = beam_->elementDof(element_, k);
}

void BeamElementItem::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const Eigen::Map<const ancf::Vec8> q(in.q);
  Eigen::Map<ancf::Vec8> r(residual);
  const ancf::Section &sec = beam_->section();
  const double l = beam_->elementLength();
  ancf::Vec8 f;
  if (!ctx.residualWanted && J && ctx.kin.cQ == 0.0) {
    // Only a mass or damping Jacobian (the eigen-analysis' B and D passes):
    // no internal force. The same operations on J as the general path below.
    Eigen::Map<Eigen::Matrix<double, 8, 8, Eigen::RowMajor>> Jm(J);
    Jm = ctx.kin.cA * (*mass_);
    if (sec.damped() && ctx.kin.cV != 0.0) {
      const Eigen::Map<const ancf::Vec8> v(in.v);
      ancf::Vec8 fd;
      ancf::Mat8 Dv;
      ancf::dampingForce(sec, l, q, v, fd, nullptr, &Dv);
      Jm += ctx.kin.cV * Dv;
    }
    return;
  }
  if (!J && sec.damped()) {
    // A residual of a damped element: both forces in one pass over the Gauss
    // points, bit-identical to internalForce + addDamping below.
    const Eigen::Map<const ancf::Vec8> v(in.v);
    ancf::Vec8 fd;
    const double power = ancf::internalAndDampingForce(sec, l, q, v, f, fd);
    inertiaAndForces(in.a, f, ctx.loadFactor, residual);
    r += fd;
    // Kept for dampingAt: the last residual of a converged step is
    // evaluated at the state the step ends on, whose energy diagnostics and
    // energy check then need these forces again.
    DampingMemo &m = dampingMemo_;
    m.q = q, m.v = v, m.fd = fd, m.power = power, m.valid = true;
    return;
  }
  if (J && ctx.kin.cQ != 0.0) {
    ancf::Mat8 K;
    ancf::internalForce(sec, l, q, f, &K);
    Eigen::Map<Eigen::Matrix<double, 8, 8, Eigen::RowMajor>> Jm(J);
    Jm = ctx.kin.cA * (*mass_) + ctx.kin.cQ * K;
  } else {
    ancf::internalForce(sec, l, q, f, nullptr);
    if (J) Eigen::Map<Eigen::Matrix<double, 8, 8, Eigen::RowMajor>>{J} = ctx.kin.cA * (*mass_);
  }
  inertiaAndForces(in.a, f, ctx.loadFactor, residual);
  // Undamped sections skip this entirely (no cost, results bit-identical).
  if (sec.damped()) addDamping(ctx, in, residual, J);
}

const void *BeamElementItem::residualBatchKey() const { return static_cast<const void *>(beam_); }

void BeamElementItem::evaluateResiduals(const AssemblyContext &ctx, const WorkItem *const items[],
                                        const ItemValues in[], double *const residual[], int count) const
{
  static_assert(ancf::kForceBatch == kResidualBatch, "one kernel call per batch of residuals");
  if (count != ancf::kForceBatch) {
    WorkItem::evaluateResiduals(ctx, items, in, residual, count);
    return;
  }
  // The residual paths of evaluate() on lanes, one element per lane: the
  // internal force (undamped), or internal and damping force with the
  // dissipated power (damped), then inertiaAndForces (+ fd). The items
  // share this item's beam (same key), so its length and section.
  using Lanes = ancf::ForceLanes;
  const BeamElementItem *const *beams = reinterpret_cast<const BeamElementItem *const *>(items);
  const ancf::Section &sec = beam_->section();
  const bool damped = sec.damped();
  const double *qs[lanes::kWidth], *as[lanes::kWidth], *gs[lanes::kWidth];
  for (int j = 0; j < lanes::kWidth; ++j) qs[j] = in[j].q, as[j] = in[j].a, gs[j] = beams[j]->gravity_.data();
  Lanes q[8], f[8], fd[8];
  lanes::gatherLanes(qs, 0, q), lanes::gatherLanes(qs, 4, q + 4);
  if (damped) {
    const double *vs[lanes::kWidth];
    double *fds[lanes::kWidth];
    for (int j = 0; j < lanes::kWidth; ++j) vs[j] = in[j].v, fds[j] = beams[j]->dampingMemo_.fd.data();
    Lanes v[8];
    lanes::gatherLanes(vs, 0, v), lanes::gatherLanes(vs, 4, v + 4);
    const Lanes power = ancf::internalAndDampingForceLanes(sec, beam_->elementLength(), q, v, f, fd);
    // Each item keeps its damping force and power for dampingAt, as evaluate() does.
    lanes::scatterLanes(fd, fds, 0), lanes::scatterLanes(fd + 4, fds, 4);
    for (int j = 0; j < lanes::kWidth; ++j) {
      DampingMemo &m = beams[j]->dampingMemo_;
      m.q = Eigen::Map<const ancf::Vec8>(in[j].q), m.v = Eigen::Map<const ancf::Vec8>(in[j].v);
      m.power = power[j], m.valid = true;
    }
  } else {
    ancf::internalForceLanes(sec, beam_->elementLength(), q, f);
  }
  bool sameMass = kroneckerMass_;
  for (int j = 1; j < count; ++j) sameMass = sameMass && beams[j]->mass_ == mass_;
  if (!sameMass) {
    for (int j = 0; j < count; ++j) {
      ancf::Vec8 fj;
      for (int i = 0; i < 8; ++i) fj[i] = f[i][j];
      beams[j]->inertiaAndForces(in[j].a, fj, ctx.loadFactor, residual[j]);
      if (damped) Eigen::Map<ancf::Vec8>{residual[j]} += beams[j]->dampingMemo_.fd;
    }
    return;
  }
  // inertiaAndForces' Kronecker path lane by lane: per entry 2i+d the
  // products m_ik a_(2k+d) summed from zero in k's order, then
  // (s + f) - loadFactor g, each item with its own gravity force; then + fd
  // when damped (evaluate()'s r += fd).
  const ancf::Mat8 &M = *mass_;
  Lanes a[8], g[8], r[8];
  lanes::gatherLanes(as, 0, a), lanes::gatherLanes(as, 4, a + 4);
  lanes::gatherLanes(gs, 0, g), lanes::gatherLanes(gs, 4, g + 4);
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 2; ++d) {
      Lanes s{};
      for (int k = 0; k < 4; ++k) s += M(2 * i, 2 * k) * a[2 * k + d];
      r[2 * i + d] = (s + f[2 * i + d]) - ctx.loadFactor * g[2 * i + d];
    }
  if (damped)
    for (int i = 0; i < 8; ++i) r[i] += fd[i];
  lanes::scatterLanes(r, residual, 0), lanes::scatterLanes(r + 4, residual, 4);
}

void BeamElementItem::evaluatePencil(const PencilPass (&pass)[kPencilPasses], int n, double *scratch) const
{
  const PencilPass &A = pass[0], &B = pass[1], &D = pass[2];
  const ancf::Section &sec = beam_->section();
  const auto same = [](const double *x, const double *y) { return std::memcmp(x, y, 8 * sizeof(double)) == 0; };
  // What evaluate() does in the three passes of Assembler::evaluatePencil,
  // Jacobian only (the residual is discarded): A (cQ != 0, cV = 0) takes the
  // tangent path, K and then dfd/dq; B and D (cQ = 0) the mass-or-damping
  // path, dfd/dv for cV != 0. A's and D's damping kernels run on the same
  // (q, v) (bitwise: the maps differ only in the sign of zero entries, and
  // then this falls back) and one call gives both matrices, each summed as
  // in its own call. Any other arrangement: the three evaluate() calls.
  const bool shaped = sec.damped() && A.J && D.J && !A.ctx.residualWanted && !B.ctx.residualWanted &&
                      !D.ctx.residualWanted && A.ctx.kin.cQ != 0.0 && A.ctx.kin.cV == 0.0 &&
                      B.ctx.kin.cQ == 0.0 && B.ctx.kin.cV == 0.0 && D.ctx.kin.cQ == 0.0 &&
                      D.ctx.kin.cV != 0.0 && same(A.in.q, D.in.q) && same(A.in.v, D.in.v);
  if (!shaped) {
    WorkItem::evaluatePencil(pass, n, scratch);
    return;
  }
  using RowMajor8 = Eigen::Matrix<double, 8, 8, Eigen::RowMajor>;
  const Eigen::Map<const ancf::Vec8> q(A.in.q), v(A.in.v);
  const double l = beam_->elementLength();
  ancf::Vec8 f, fd;
  ancf::Mat8 K, Kq, Dv;
  // At rest (the eigen-analysis' v = 0) one kernel for both; else the two.
  if (!ancf::stiffnessAndDampingAtRest(sec, l, q, v, K, Kq, Dv)) {
    ancf::internalForce(sec, l, q, f, &K);
    ancf::dampingForce(sec, l, q, v, fd, &Kq, &Dv);
  }
  Eigen::Map<RowMajor8> Ja(A.J);
  Ja = A.ctx.kin.cA * (*mass_) + A.ctx.kin.cQ * K;
  Ja += A.ctx.kin.cQ * Kq;
  if (B.J) Eigen::Map<RowMajor8>{B.J} = B.ctx.kin.cA * (*mass_);
  Eigen::Map<RowMajor8> Jd(D.J);
  Jd = D.ctx.kin.cA * (*mass_);
  Jd += D.ctx.kin.cV * Dv;
}

void BeamElementItem::addDamping(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const Eigen::Map<const ancf::Vec8> q(in.q), v(in.v);
  Eigen::Map<ancf::Vec8> r(residual);
  const ancf::Section &sec = beam_->section();
  const double l = beam_->elementLength();
  ancf::Vec8 fd;
  const bool wantQ = J && ctx.kin.cQ != 0.0, wantV = J && ctx.kin.cV != 0.0;
  ancf::Mat8 Kq, Dv;
  ancf::dampingForce(sec, l, q, v, fd, wantQ ? &Kq : nullptr, wantV ? &Dv : nullptr);
  r += fd;
  if (!J) return;
  Eigen::Map<Eigen::Matrix<double, 8, 8, Eigen::RowMajor>> Jm(J);
  if (wantQ) Jm += ctx.kin.cQ * Kq;
  if (wantV) Jm += ctx.kin.cV * Dv;
}

void BeamElementItem::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  ancf::Vec8 fd;
  energyAt(ctx, in, e, fd);
}

bool BeamElementItem::energyAndDampingForce(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e,
                                            double *f) const
{
  ancf::Vec8 fd;
  energyAt(ctx, in, e, fd);
  if (!beam_->section().damped()) return false;
  Eigen::Map<ancf::Vec8>{f} = fd;
  return true;
}

void BeamElementItem::energyAt(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e, ancf::Vec8 &fd) const
{
  const Eigen::Map<const ancf::Vec8> q(in.q), v(in.v);
  e.kinetic += 0.5 * v.dot(massTimes(in.v));
  const ancf::Section &sec = beam_->section();
  const double l = beam_->elementLength(), u = ancf::strainEnergy(sec, l, q);
  e.strain += u;
  if (sec.damped()) e.dissipation += dampingAt(in, fd);
  // Round-off of the curvature eps |q| / l^2 and of the axial strain eps |q| / l,
  // entering U = l (EA eps^2 + EI kappa^2) / 2 to first order through the
  // strain present and to second order on their own.
  const double eps = std::numeric_limits<double>::epsilon(), size = q.cwiseAbs().maxCoeff();
  const double dk = eps * size / (l * l), de = eps * size / l;
  e.roundoff += 2.0 * std::sqrt(2.0 * std::abs(u) * l) * (std::sqrt(sec.EI) * dk + std::sqrt(sec.EA) * de) +
                l * (sec.EI * dk * dk + sec.EA * de * de);
  // Gravity is a constant generalized force: V = -Q_g . e.
  e.potential -= ctx.loadFactor * gravity_.dot(q);
}

bool BeamElementItem::physicalDamping() const { return beam_->section().damped(); }

bool BeamElementItem::dampingForce(const ItemValues &in, double *f) const
{
  const ancf::Section &sec = beam_->section();
  if (!sec.damped()) return false;
  ancf::Vec8 fd;
  (void)dampingAt(in, fd);
  Eigen::Map<ancf::Vec8> out(f);
  out = fd;
  return true;
}

double BeamElementItem::dampingAt(const ItemValues &in, ancf::Vec8 &fd) const
{
  const Eigen::Map<const ancf::Vec8> q(in.q), v(in.v);
  DampingMemo &m = dampingMemo_;
  if (!(m.valid && m.q == q && m.v == v)) {
    m.power = ancf::dampingForce(beam_->section(), beam_->elementLength(), q, v, m.fd, nullptr, nullptr);
    m.q = q, m.v = v, m.valid = true;
  }
  fd = m.fd;
  return m.power;
}

void BeamElementItem::scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const
{
  const Eigen::Map<const ancf::Vec8> q(in.q);
  ancf::Vec8 f;
  ancf::Mat8 K;
  ancf::internalForce(beam_->section(), beam_->elementLength(), q, f, &K);
  // Position entries only: slope entries carry other units (kg m^2).
  for (int k : {0, 1, 4, 5}) {
    massDiag += (*mass_)(k, k);
    stiffDiag += K(k, k);
  }
  count += 4;
}

} // namespace boomdyn

namespace boomdyn {

void BeamElementItem::modeEnergy(const PencilPass &stiffness, int n, const double *shape, double *scratch,
                                 ModeEnergy &out) const
{
  // The whole tangent's 1/2 s^T K s, and its material part strain by strain:
  // the Kelvin-Voigt power of the rate edot = s with a unit retardation time
  // on one strain only is s^T K_material s of that strain (the damping law
  // is eta times the material stiffness, axial projection included), so the
  // kernel that integrates it serves as the split. The rest of the tangent
  // (N d2eps/de2 + M d2K/de2: stress stiffening) is geometric.
  ModeEnergy whole;
  WorkItem::modeEnergy(stiffness, n, shape, scratch, whole);
  const double total = whole.kind[static_cast<int>(ModeEnergyKind::Geometric)];
  const ancf::Vec8 q = Eigen::Map<const ancf::Vec8>(stiffness.in.q), s = Eigen::Map<const ancf::Vec8>(shape);
  ancf::Section axial = beam_->section(), bending = beam_->section();
  axial.etaA = 1, axial.etaB = 0, bending.etaA = 0, bending.etaB = 1;
  ancf::Vec8 fd;
  const double l = beam_->elementLength();
  const double ea = 0.5 * ancf::dampingForce(axial, l, q, s, fd, nullptr, nullptr);
  const double eb = 0.5 * ancf::dampingForce(bending, l, q, s, fd, nullptr, nullptr);
  out.add(ModeEnergyKind::Axial, ea);
  out.add(ModeEnergyKind::BendingInPlane, eb);
  out.add(ModeEnergyKind::Geometric, total - ea - eb);
}

} // namespace boomdyn
