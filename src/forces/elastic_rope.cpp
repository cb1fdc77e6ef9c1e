#include "boomdyn/elastic_rope.hpp"

namespace boomdyn {

ElasticRope::ElasticRope(std::string name, RopePath path, double EA, double restLength, double damping)
  : name_(std::move(name)), path_(std::move(path)), EA_(EA), L0_(restLength), c_(damping)
{
}

ElasticRope::State ElasticRope::state(const double *q, const double *v) const
{
  State st;
  Eigen::RowVectorXd lq;
  st.length = path_.evaluate(q, lq);
  st.rate = lq.dot(Eigen::Map<const Eigen::VectorXd>(v, path_.numCoordinates()));
  st.stretch = st.length - L0_;
  st.force = stiffness() * st.stretch + c_ * st.rate;
  // Tension only, and only while longer than unstretched: a rope shorter
  // than L0 carries nothing even while it lengthens fast (no damping pull).
  st.taut = st.stretch > 0 && st.force > 0;
  st.tension = st.taut ? st.force : 0.0;
  return st;
}

void ElasticRope::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const int n = path_.numCoordinates();
  Eigen::RowVectorXd lq;
  Eigen::MatrixXd lqq = Eigen::MatrixXd::Zero(n, n);
  const double l = path_.evaluate(in.q, lq, 1.0, &lqq);
  const Eigen::Map<const Eigen::VectorXd> v(in.v, n);
  const double rate = lq.dot(v), k = stiffness(), f = k * (l - L0_) + c_ * rate;
  if (!(l > L0_ && f > 0)) return; // slack: no force, no stiffness
  // The active set is that of the current Newton iterate (a semismooth
  // Newton step); a step whose iteration does not converge is cut by the
  // step controller.
  for (int i = 0; i < n; ++i) residual[i] += f * lq[i];
  if (!J) return;
  const Kinematics &kin = ctx.kin;
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Jm(J, n, n);
  const Eigen::VectorXd lqqv = lqq * v; // d(dl/dt)/dq = (l_qq v)^T
  Jm += kin.cQ * (f * lqq + k * lq.transpose() * lq + c_ * lq.transpose() * lqqv.transpose()) +
        kin.cV * c_ * lq.transpose() * lq;
}

void ElasticRope::energy(const AssemblyContext &, const ItemValues &in, EnergyParts &e) const
{
  const State st = state(in.q, in.v);
  const double elastic = st.stretch > 0 ? stiffness() * st.stretch : 0.0;
  if (st.stretch > 0) e.strain += 0.5 * stiffness() * st.stretch * st.stretch;
  // Power into the rope T l' minus the rate of its strain energy: >= 0 in every case of the cut.
  e.dissipation += st.tension * st.rate - elastic * st.rate;
}

} // namespace boomdyn
