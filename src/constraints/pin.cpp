#include "boomdyn/pin.hpp"

namespace boomdyn {

Pin::Pin(std::string name, const Body &a, double sa, Vec2 ground)
  : name_(std::move(name)), a_(&a), sa_(sa), la_(a.locate(sa)), ground_(ground)
{
}

Pin::Pin(std::string name, const Body &a, double sa, const Body &b, double sb)
  : name_(std::move(name)), a_(&a), b_(&b), sa_(sa), sb_(sb), la_(a.locate(sa)), lb_(b.locate(sb))
{
}

void Pin::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(la_.dofs.begin(), la_.dofs.begin() + la_.count);
  if (b_) dofs.insert(dofs.end(), lb_.dofs.begin(), lb_.dofs.begin() + lb_.count);
}

void Pin::evaluate(double, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  const int na = la_.count, nb = b_ ? lb_.count : 0, n = na + nb;
  CenterlineSample pa, pb;
  a_->sample(la_, sa_, q, pa);
  out.C = pa.r[0] - ground_;
  out.Cq.setZero(2, n);
  out.Cq.leftCols(na) = pa.r_q[0].leftCols(na);
  if (b_) {
    b_->sample(lb_, sb_, q + na, pb);
    out.C -= pb.r[0];
    out.Cq.rightCols(nb) = -pb.r_q[0].leftCols(nb);
  }
  // Second q-derivatives only where a centerline is nonlinear in q (rigid bodies).
  auto hessian = [&](const Body &body, const CenterlineLocation &loc, double s, const double *vals,
                     const CenterlineSample &p, const Vec2 &weight, Eigen::Matrix<double, 8, 8> &H) {
    if (p.linear) H.setZero();
    else body.curvatureTerm(loc, s, vals, 0, weight, H);
  };
  if (v) {
    out.gamma.setZero(2);
    Eigen::Matrix<double, 8, 8> H;
    for (int i = 0; i < 2; ++i) {
      const Vec2 ei = Vec2::Unit(i);
      hessian(*a_, la_, sa_, q, pa, ei, H);
      out.gamma[i] += Eigen::Map<const Eigen::VectorXd>(v, na).dot(H.topLeftCorner(na, na) * Eigen::Map<const Eigen::VectorXd>(v, na));
      if (b_) {
        hessian(*b_, lb_, sb_, q + na, pb, -ei, H);
        out.gamma[i] += Eigen::Map<const Eigen::VectorXd>(v + na, nb).dot(H.topLeftCorner(nb, nb) * Eigen::Map<const Eigen::VectorXd>(v + na, nb));
      }
    }
  }
  if (w) {
    out.H.setZero(n, n);
    Eigen::Matrix<double, 8, 8> H;
    const Vec2 weight(w[0], w[1]);
    hessian(*a_, la_, sa_, q, pa, weight, H);
    out.H.topLeftCorner(na, na) = H.topLeftCorner(na, na);
    if (b_) {
      hessian(*b_, lb_, sb_, q + na, pb, -weight, H);
      out.H.bottomRightCorner(nb, nb) = H.topLeftCorner(nb, nb);
    }
  }
}

} // namespace boomdyn
