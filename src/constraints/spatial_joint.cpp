#include "boomdyn/spatial_joint.hpp"

#include <cmath>

namespace boomdyn {

namespace {

// A vector fixed in the section triad: value T c, its Jacobian sum c_k d(d_k)/dq.
void fixedVector(const SpatialSample &p, const Vec3 &c, int n, Vec3 &value, Eigen::MatrixXd &jac)
{
  value = p.triad * c;
  jac = c[0] * p.d_q[0].leftCols(n) + c[1] * p.d_q[1].leftCols(n) + c[2] * p.d_q[2].leftCols(n);
}

// d2(w . T c)/dq2 = sum_k c_k d2(w . d_k)/dq2, added (times f) to H.
void addVectorHessian(const SpatialEnd &e, const double *q, const Vec3 &c, const Vec3 &w, double f,
                      Eigen::Ref<Eigen::MatrixXd> H)
{
  SpatialHessian h;
  const int n = e.loc.count;
  for (int k = 0; k < 3; ++k) {
    if (c[k] == 0.0) continue;
    e.body->curvatureTerm(e.loc, e.s, q, static_cast<SpatialField>(k + 1), w, h);
    H += (f * c[k]) * h.topLeftCorner(n, n);
  }
}

} // namespace

void frameAcross(const Vec3 &axis, const Vec3 &hint, Vec3 &n1, Vec3 &n2)
{
  const Vec3 a = axis.normalized();
  Vec3 h = hint - hint.dot(a) * a;
  if (h.norm() < 1e-9 * std::max(1.0, hint.norm())) {
    // Any normal: the unit vector least aligned with the axis, projected.
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(a[i]) < std::abs(a[k])) k = i;
    h = Vec3::Unit(k) - a[k] * a;
  }
  n1 = h.normalized();
  n2 = a.cross(n1);
}

SpatialJoint::SpatialJoint(std::string name, SpatialEnd a, SpatialEnd b, bool position,
                           std::vector<SpatialOffsetRow> offsets, std::vector<SpatialDotRow> rows, bool driven)
  : name_(std::move(name)), a_(std::move(a)), b_(std::move(b)), position_(position), offsets_(std::move(offsets)),
    rows_(std::move(rows)), driven_(driven)
{
}

void SpatialJoint::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(a_.loc.dofs.begin(), a_.loc.dofs.begin() + a_.loc.count);
  if (b_.body) dofs.insert(dofs.end(), b_.loc.dofs.begin(), b_.loc.dofs.begin() + b_.loc.count);
}

void SpatialJoint::velocityBreakpoints(std::vector<double> &out) const
{
  for (const SpatialOffsetRow &r : offsets_) r.shift.velocityBreakpoints(out);
  for (const SpatialDotRow &r : rows_) r.theta.velocityBreakpoints(out);
}

void SpatialJoint::accelerationBreakpoints(std::vector<double> &out) const
{
  for (const SpatialOffsetRow &r : offsets_) r.shift.accelerationBreakpoints(out);
  for (const SpatialDotRow &r : rows_) r.theta.accelerationBreakpoints(out);
}

const char *SpatialJoint::rowUnit(int row) const
{
  row -= position_ ? 3 : 0;
  if (row < 0 || row < static_cast<int>(offsets_.size())) return "m";
  return rows_[row - offsets_.size()].unit;
}

void SpatialJoint::evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  const int na = a_.loc.count, nb = b_.body ? b_.loc.count : 0, n = na + nb, m = numRows();
  const double *qb = q + na;
  SpatialSample pa, pb;
  a_.body->sample(a_.loc, a_.s, q, pa);
  if (b_.body) b_.body->sample(b_.loc, b_.s, qb, pb);
  out.C.resize(m);
  out.Cq.setZero(m, n);
  if (v) out.gamma.setZero(m), out.Ct.setZero(m);
  if (w) out.H.setZero(n, n);
  Eigen::Map<const Eigen::VectorXd> va(v ? v : q, na), vb(v ? v + na : q, nb);
  SpatialHessian h;
  int row = 0;
  if (position_) {
    out.C.head<3>() = pa.r - (b_.body ? pb.r : b_.point);
    out.Cq.block(0, 0, 3, na) = pa.r_q.leftCols(na);
    if (b_.body) out.Cq.block(0, na, 3, nb) = -pb.r_q.leftCols(nb);
    if (v)
      for (int c = 0; c < 3; ++c) {
        a_.body->curvatureTerm(a_.loc, a_.s, q, SpatialField::Position, Vec3::Unit(c), h);
        out.gamma[c] += va.dot(h.topLeftCorner(na, na) * va);
        if (b_.body) {
          b_.body->curvatureTerm(b_.loc, b_.s, qb, SpatialField::Position, Vec3::Unit(c), h);
          out.gamma[c] -= vb.dot(h.topLeftCorner(nb, nb) * vb);
        }
      }
    if (w) {
      const Vec3 wp(w[0], w[1], w[2]);
      a_.body->curvatureTerm(a_.loc, a_.s, q, SpatialField::Position, wp, h);
      out.H.topLeftCorner(na, na) += h.topLeftCorner(na, na);
      if (b_.body) {
        b_.body->curvatureTerm(b_.loc, b_.s, qb, SpatialField::Position, -wp, h);
        out.H.bottomRightCorner(nb, nb) += h.topLeftCorner(nb, nb);
      }
    }
    row = 3;
  }
  if (!offsets_.empty()) {
    // C = d . T_b c - base - f(t) with the separation d = r_a - r_b.
    const Vec3 d = pa.r - (b_.body ? pb.r : b_.point);
    Vec3 dd = Vec3::Zero(); // its rate, without the acceleration part
    if (v) dd = pa.r_q.leftCols(na) * va - (b_.body ? Vec3(pb.r_q.leftCols(nb) * vb) : Vec3::Zero());
    Vec3 e;
    Eigen::MatrixXd eq;
    for (const SpatialOffsetRow &o : offsets_) {
      if (b_.body) fixedVector(pb, o.c, nb, e, eq);
      else e = o.c;
      out.C[row] = d.dot(e) - o.base - o.shift.value(t);
      out.Cq.block(row, 0, 1, na) = e.transpose() * pa.r_q.leftCols(na);
      if (b_.body) out.Cq.block(row, na, 1, nb) = d.transpose() * eq - e.transpose() * pb.r_q.leftCols(nb);
      if (v) {
        // d2C/dt2 = C_q a + gamma: d'' . e + 2 d' . e' + d . e'' - f''.
        a_.body->curvatureTerm(a_.loc, a_.s, q, SpatialField::Position, e, h);
        double g = va.dot(h.topLeftCorner(na, na) * va);
        if (b_.body) {
          b_.body->curvatureTerm(b_.loc, b_.s, qb, SpatialField::Position, -e, h);
          Eigen::MatrixXd Hb = h.topLeftCorner(nb, nb);
          addVectorHessian(b_, qb, o.c, d, 1.0, Hb);
          g += vb.dot(Hb * vb) + 2.0 * dd.dot(eq * vb);
        }
        if (driven_) {
          out.Ct[row] = -o.shift.rate(t);
          g -= o.shift.accel(t);
        }
        out.gamma[row] = g;
      }
      if (w && w[row] != 0.0) {
        const double wr = w[row];
        a_.body->curvatureTerm(a_.loc, a_.s, q, SpatialField::Position, wr * e, h);
        out.H.topLeftCorner(na, na) += h.topLeftCorner(na, na);
        if (b_.body) {
          b_.body->curvatureTerm(b_.loc, b_.s, qb, SpatialField::Position, -wr * e, h);
          out.H.bottomRightCorner(nb, nb) += h.topLeftCorner(nb, nb);
          addVectorHessian(b_, qb, o.c, d, wr, out.H.bottomRightCorner(nb, nb));
          const Eigen::MatrixXd rbe = pb.r_q.leftCols(nb).transpose() * eq;
          out.H.bottomRightCorner(nb, nb) -= wr * (rbe + rbe.transpose());
          const Eigen::MatrixXd cross = wr * pa.r_q.leftCols(na).transpose() * eq;
          out.H.topRightCorner(na, nb) += cross;
          out.H.bottomLeftCorner(nb, na) += cross.transpose();
        }
      }
      ++row;
    }
  }
  Vec3 u, vv;
  Eigen::MatrixXd uq, vq;
  for (const SpatialDotRow &d : rows_) {
    const double th = d.theta.value(t), c = std::cos(th), s = std::sin(th);
    const Vec3 vb0 = -s * d.n1 + c * d.n2; // v' in b's axes
    fixedVector(pa, d.u, na, u, uq);
    if (b_.body) fixedVector(pb, vb0, nb, vv, vq);
    else vv = vb0;
    out.C[row] = u.dot(vv);
    out.Cq.block(row, 0, 1, na) = vv.transpose() * uq;
    if (b_.body) out.Cq.block(row, na, 1, nb) = u.transpose() * vq;
    if (v) {
      // d2C/dt2 = C_q a + gamma: the quadratic velocity terms, then those of theta(t).
      const Vec3 ud = uq * va, vd = b_.body ? Vec3(vq * vb) : Vec3::Zero();
      Eigen::MatrixXd Ha = Eigen::MatrixXd::Zero(na, na);
      addVectorHessian(a_, q, d.u, vv, 1.0, Ha);
      double g = va.dot(Ha * va) + 2.0 * ud.dot(vd);
      if (b_.body) {
        Eigen::MatrixXd Hb = Eigen::MatrixXd::Zero(nb, nb);
        addVectorHessian(b_, qb, vb0, u, 1.0, Hb);
        g += vb.dot(Hb * vb);
      }
      if (driven_) {
        const double rate = d.theta.rate(t), acc = d.theta.accel(t);
        const Vec3 i0 = c * d.n1 + s * d.n2;       // dv'/dtheta = -i'
        const Vec3 vt0 = -rate * i0, vtt0 = -acc * i0 - rate * rate * vb0;
        Vec3 vt = vt0, vtt = vtt0, vtd = Vec3::Zero();
        if (b_.body) {
          Eigen::MatrixXd vtq;
          fixedVector(pb, vt0, nb, vt, vtq);
          vtt = pb.triad * vtt0;
          vtd = vtq * vb;
        }
        g += 2.0 * (ud.dot(vt) + u.dot(vtd)) + u.dot(vtt);
        out.Ct[row] = u.dot(vt);
      }
      out.gamma[row] = g;
    }
    if (w && w[row] != 0.0) {
      const double wr = w[row];
      addVectorHessian(a_, q, d.u, vv, wr, out.H.topLeftCorner(na, na));
      if (b_.body) {
        addVectorHessian(b_, qb, vb0, u, wr, out.H.bottomRightCorner(nb, nb));
        const Eigen::MatrixXd cross = wr * uq.transpose() * vq;
        out.H.topRightCorner(na, nb) += cross;
        out.H.bottomLeftCorner(nb, na) += cross.transpose();
      }
    }
    ++row;
  }
}

} // namespace boomdyn
