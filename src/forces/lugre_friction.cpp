#include "boomdyn/lugre_friction.hpp"

#include "boomdyn/pad_contact.hpp"

#include <unsupported/Eigen/AutoDiff>

#include <array>
#include <cmath>

namespace boomdyn {

namespace {
// Derivatives with respect to the item's unknowns: at most two 8-coordinate
// elements, s, z and the normal multiplier. A fixed capacity keeps them on
// the stack (a heap-allocated VectorXd per intermediate made one friction
// item cost as much as 25 beam elements).
constexpr int kMaxUnknowns = 19;
using Derivatives = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxUnknowns, 1>;
using AD = Eigen::AutoDiffScalar<Derivatives>;

AD absolute(const AD &x) { return x.value() < 0 ? AD(-x) : x; }
} // namespace

LuGreFriction::LuGreFriction(std::shared_ptr<const SlidingJoint> joint, PetscInt zIndex, PetscInt normalRow,
                             const FrictionSpec &spec)
  : joint_(std::move(joint)), z_(zIndex), normalRow_(normalRow), spec_(spec)
{
}

LuGreFriction::LuGreFriction(std::shared_ptr<const SlidingJoint> joint, PetscInt zIndex, const PadContact *pad,
                             const FrictionSpec &spec)
  : joint_(std::move(joint)), z_(zIndex), normalRow_(-1), spec_(spec), pad_(pad)
{
}

void LuGreFriction::coordinates(std::vector<PetscInt> &dofs) const
{
  joint_->coordinates(dofs); // track element, slider element, slack s
  dofs.push_back(z_);
}

double LuGreFriction::stribeck(double v) const
{
  return spec_.mu_c + (spec_.mu_s - spec_.mu_c) * std::exp(-std::pow(std::abs(v / spec_.v_s), spec_.alpha));
}

void LuGreFriction::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const CenterlineLocation &tl = joint_->trackLocation(), &sl = joint_->sliderLocation();
  // Unknowns: track element, slider element, s, z, then lambda_n (none with a pad).
  const int ni = tl.count, nj = sl.count, is = ni + nj, iz = is + 1, il = iz + 1, n = pad_ ? il : il + 1;
  const Kinematics &k = ctx.kin;
  const bool integrate = k.cZ > 0, accelerationLevel = ctx.accelerationLevel;
  // The mass pencil of an eigen-analysis (cQ = 0 away from the acceleration
  // level): friction has no inertia, and z must not get a mass.
  if (k.cQ == 0 && !accelerationLevel) return;

  auto variable = [&](double value, int index, double coefficient) {
    AD a(value, n, index);
    a.derivatives() *= coefficient;
    return a;
  };
  auto constant = [&](double value) { return AD(value, Derivatives::Zero(n)); };

  const double sv = in.q[is];
  CenterlineSample ti, sj;
  joint_->track().sample(tl, sv, in.q, ti);
  joint_->slider().sample(sl, joint_->sliderPoint(), in.q + ni, sj);
  // Second q-derivatives of the positions, per component (rigid bodies only).
  Eigen::Matrix<double, 8, 8> Hi[2], Hj[2];
  for (int c = 0; c < 2; ++c) {
    Hi[c].setZero(), Hj[c].setZero();
    if (!ti.linear) joint_->track().curvatureTerm(tl, sv, in.q, 0, Vec2::Unit(c), Hi[c]);
    if (!sj.linear) joint_->slider().curvatureTerm(sl, joint_->sliderPoint(), in.q + ni, 0, Vec2::Unit(c), Hj[c]);
  }

  // d r_q[0](c, m) as an AD number: its s-derivative is r_q[1], its q-derivative the curvature term.
  auto trackJacobianEntry = [&](int c, int m) {
    AD a = constant(ti.r_q[0](c, m));
    a.derivatives()[is] += k.cQ * ti.r_q[1](c, m);
    for (int p = 0; p < ni; ++p) a.derivatives()[p] += k.cQ * Hi[c](m, p);
    return a;
  };
  auto sliderJacobianEntry = [&](int c, int m) {
    AD a = constant(sj.r_q[0](c, m));
    for (int p = 0; p < nj; ++p) a.derivatives()[ni + p] += k.cQ * Hj[c](m, p);
    return a;
  };

  // Tangent t = r_i'(s), material-point velocities of track and slider.
  AD t[2], Vi[2], Vj[2];
  for (int c = 0; c < 2; ++c) {
    t[c] = constant(ti.r[1][c]);
    t[c].derivatives()[is] += k.cQ * ti.r[2][c];
    for (int m = 0; m < ni; ++m) t[c].derivatives()[m] += k.cQ * ti.r_q[1](c, m);
    Vi[c] = constant(0.0);
    for (int m = 0; m < ni; ++m) Vi[c] += trackJacobianEntry(c, m) * variable(in.v[m], m, k.cV);
    Vj[c] = constant(0.0);
    for (int m = 0; m < nj; ++m) Vj[c] += sliderJacobianEntry(c, m) * variable(in.v[ni + m], ni + m, k.cV);
  }
  const AD length = sqrt(t[0] * t[0] + t[1] * t[1]);
  const AD ix = t[0] / length, iy = t[1] / length;
  const AD vr = ix * (Vi[0] - Vj[0]) + iy * (Vi[1] - Vj[1]);

  const FrictionSpec &f = spec_;
  const AD z = variable(in.q[iz], iz, k.cQ);
  const AD speed = absolute(vr);
  AD g = constant(f.mu_c);
  if (speed.value() > 0) g += (f.mu_s - f.mu_c) * exp(-pow(speed / f.v_s, f.alpha));
  else g += constant(f.mu_s - f.mu_c);
  const AD law = vr - f.sigma0 * speed * z / g; // zdot the LuGre law asks for
  // Dynamics: zdot from the time discretization (equal to `law` at convergence);
  // initial conditions: the law's value; statics / eigen: z frozen, no rate.
  const AD zdot = integrate ? variable(in.v[iz], iz, k.cZ) : (accelerationLevel ? law : constant(0.0));
  AD lambda;
  if (pad_) { // the pad force f(q, v) over the joint's coordinates (0 .. is)
    double fp;
    Eigen::VectorXd &fq = padFq_, &fv = padFv_;
    pad_->force(in.q, in.v, fp, fq, fv);
    lambda = constant(fp);
    for (int m = 0; m <= is; ++m) lambda.derivatives()[m] += k.cQ * fq[m] + k.cV * fv[m];
  } else
    lambda = variable(ctx.sigma * in.lambda[0], il, ctx.sigma);
  // The impulsive step of a velocity projection (velocityLevel, lambda the
  // normal impulse) is frictionless: friction acts through finite forces
  // only (docs/model.md §4.8).
  const AD force = ctx.velocityLevel ? constant(0.0)
                                     : AD((f.sigma0 * z + f.sigma1 * zdot) * absolute(lambda) + f.sigma2 * vr);

  std::array<AD, kMaxUnknowns> r;
  for (int row = 0; row < n; ++row) r[row] = constant(0.0);
  // Force -F_t i on the track at s, +F_t i on the slider: residual = -Q.
  for (int m = 0; m < ni; ++m) r[m] = force * (trackJacobianEntry(0, m) * ix + trackJacobianEntry(1, m) * iy);
  for (int m = 0; m < nj; ++m) r[ni + m] = -force * (sliderJacobianEntry(0, m) * ix + sliderJacobianEntry(1, m) * iy);
  // The z row, scaled like the mechanical rows (sigma ~ mass / h^2 in dynamics).
  const double weight = ctx.sigma / (integrate ? k.cZ : 1.0);
  if (integrate) r[iz] = weight * (zdot - law);
  else if (accelerationLevel) r[iz] = weight * variable(in.a[iz], iz, k.cA); // x_z is a dummy "acceleration": 0
  else r[iz] = weight * variable(in.q[iz], iz, k.cQ);                        // statics, eigen pencil A: z frozen

  for (int row = 0; row < n; ++row) {
    residual[row] += r[row].value();
    if (J)
      for (int col = 0; col < n; ++col) J[row * n + col] += r[row].derivatives()[col];
  }
}

} // namespace boomdyn
