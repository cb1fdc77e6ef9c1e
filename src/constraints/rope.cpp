#include "boomdyn/rope.hpp"

namespace boomdyn {

Rope::Rope(std::string name, Point p, Point q, Point r, double length)
  : name_(std::move(name)), path_({p, q, r}), length_(length)
{
}

void Rope::coordinates(std::vector<PetscInt> &dofs) const { path_.coordinates(dofs); }

double Rope::spannedLength(const double *q) const { return path_.length(q); }

// C = L - l(q): C_q = -l_q, gamma = v^T C_qq v = -v^T l_qq v and the
// multiplier-weighted Hessian -w l_qq, each summed in the order of the
// original three-point formulas (the paper scenes' digests hold bitwise).
void Rope::evaluate(double, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  const int n = path_.numCoordinates();
  const RopePath::Geometry &g = path_.geometry(q);
  double C = length_;
  for (double lj : g.segment) C -= lj;
  out.C.setConstant(1, C);
  out.Cq = -g.lq;
  if (v) {
    const Eigen::Map<const Eigen::VectorXd> vv(v, n);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
    path_.addCurvature(q, g, -1.0, H); // weights dC/dr_k = -dl/dr_k
    out.gamma.setConstant(1, RopePath::segmentRate2(g, vv, true) + vv.dot(H * vv));
  }
  if (w) {
    out.H = -w[0] * RopePath::segmentHessian(g);
    path_.addCurvature(q, g, -w[0], out.H);
  }
}

} // namespace boomdyn
