#include "boomdyn/ground_contact.hpp"

namespace boomdyn {

GroundContact::GroundContact(std::string name, const Body &body, double s, double level, double stiffness,
                             double damping)
  : name_(std::move(name)), body_(&body), s_(s), loc_(body.locate(s)), level_(level), k_(stiffness), c_(damping)
{
}

void GroundContact::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(loc_.dofs.begin(), loc_.dofs.begin() + loc_.count);
}

GroundContact::State GroundContact::state(const double *q, const double *v) const
{
  CenterlineSample p;
  body_->sample(loc_, s_, q, p);
  const int n = loc_.count;
  State st;
  st.gap = p.r[0].y() - level_;
  st.rate = p.r_q[0].row(1).head(n).dot(Eigen::Map<const Eigen::VectorXd>(v, n));
  const double f = -k_ * st.gap - c_ * st.rate;
  // Compressive only, and only while the point is below the ground line (no damping pull when it lifts fast).
  st.contact = st.gap < 0 && f > 0;
  st.force = st.contact ? f : 0.0;
  return st;
}

void GroundContact::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  CenterlineSample p;
  body_->sample(loc_, s_, in.q, p);
  const int n = loc_.count;
  const Eigen::RowVectorXd yq = p.r_q[0].row(1).head(n);
  const Eigen::Map<const Eigen::VectorXd> v(in.v, n);
  const double gap = p.r[0].y() - level_, f = -k_ * gap - c_ * yq.dot(v);
  if (!(gap < 0 && f > 0)) return; // lifted off: no force, no stiffness (semismooth Newton, as the rope)
  for (int i = 0; i < n; ++i) residual[i] -= f * yq[i];
  if (!J) return;
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Jm(J, n, n);
  Jm += ctx.kin.cV * c_ * yq.transpose() * yq + ctx.kin.cQ * k_ * yq.transpose() * yq;
  if (p.linear) return;
  // Rigid bodies: d(y_q)/dq = H_y, the curvature of the height.
  Eigen::Matrix<double, 8, 8> H8;
  body_->curvatureTerm(loc_, s_, in.q, 0, Vec2(0, 1), H8);
  const Eigen::MatrixXd Hy = H8.topLeftCorner(n, n);
  const Eigen::VectorXd Hyv = Hy * v;
  Jm += ctx.kin.cQ * (c_ * yq.transpose() * Hyv.transpose() - f * Hy);
}

void GroundContact::energy(const AssemblyContext &, const ItemValues &in, EnergyParts &e) const
{
  const State st = state(in.q, in.v);
  const double elastic = st.gap < 0 ? -k_ * st.gap : 0.0;
  if (st.gap < 0) e.strain += 0.5 * k_ * st.gap * st.gap;
  // Power the body gives the contact (-F_n g') less the rate of its strain energy (-elastic g').
  e.dissipation += -st.force * st.rate + elastic * st.rate;
}

} // namespace boomdyn
