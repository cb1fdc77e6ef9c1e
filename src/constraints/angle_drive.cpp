#include "boomdyn/angle_drive.hpp"

#include <cmath>

namespace boomdyn {

AngleDrive::AngleDrive(std::string name, const Body &body, double s, TimeFunction theta)
  : name_(std::move(name)), body_(&body), s_(s), loc_(body.locate(s)), theta_(std::move(theta))
{
}

void AngleDrive::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(loc_.dofs.begin(), loc_.dofs.begin() + loc_.count);
}

void AngleDrive::evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  const int n = loc_.count;
  const double th = theta_.value(t), thd = theta_.rate(t), thdd = theta_.accel(t);
  const Vec2 i(std::cos(th), std::sin(th)), j(-std::sin(th), std::cos(th));
  CenterlineSample p;
  body_->sample(loc_, s_, q, p);
  const Vec2 &r1 = p.r[1];
  out.C.resize(1);
  out.C[0] = j.dot(r1);
  out.Cq = (j.transpose() * p.r_q[1].leftCols(n));
  Eigen::Matrix<double, 8, 8> H;
  if (v) {
    // d/dt j = -thd i, d/dt i = thd j:
    // d2C/dt2 = j.r1'' - 2 thd i.r1' - thdd i.r1 - thd^2 j.r1
    const Eigen::Map<const Eigen::VectorXd> vv(v, n);
    const Vec2 r1dot = p.r_q[1].leftCols(n) * vv;
    double quad = 0;
    if (!p.linear) {
      body_->curvatureTerm(loc_, s_, q, 1, j, H);
      quad = vv.dot(H.topLeftCorner(n, n) * vv);
    }
    out.gamma.resize(1);
    out.gamma[0] = quad - 2.0 * thd * i.dot(r1dot) - thdd * i.dot(r1) - thd * thd * j.dot(r1);
    out.Ct.setConstant(1, -thd * i.dot(r1)); // dC/dt at fixed q: (d/dt j) . r1
  }
  if (w) {
    out.H.setZero(n, n);
    if (!p.linear) {
      body_->curvatureTerm(loc_, s_, q, 1, w[0] * j, H);
      out.H = H.topLeftCorner(n, n);
    }
  }
}

} // namespace boomdyn
