#include "boomdyn/spatial_ancf_beam.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace boomdyn {

namespace sb = spatial_beam;

SpatialAncfBeam::SpatialAncfBeam(std::string name, double length, int elements, const sb::Section &section,
                                 const Vec3 &origin, const Mat3 &triad, PetscInt first)
  : SpatialBody(std::move(name), length, first), elements_(elements), section_(section), origin_(origin),
    triad_(triad), geometry_(sb::straightGeometry(triad, length / elements))
{
}

void SpatialAncfBeam::initialCoordinates(double *q) const
{
  const double l = geometry_.l;
  for (int n = 0; n <= elements_; ++n) {
    Eigen::Map<Vec3>(q + 7 * n) = origin_ + (n * l) * triad_.col(0);
    Eigen::Map<Vec3>(q + 7 * n + 3) = triad_.col(0);
    q[7 * n + 6] = 0.0;
  }
}

SpatialLocation SpatialAncfBeam::locate(double s) const
{
  const double l = geometry_.l;
  const int el = std::clamp(static_cast<int>(std::floor(s / l)), 0, elements_ - 1);
  SpatialLocation loc;
  loc.count = sb::kCoordinates;
  loc.element = el;
  loc.begin = el * l;
  loc.end = el == elements_ - 1 ? length_ : (el + 1) * l;
  loc.s = s;
  loc.xi = (s - loc.begin) / l;
  for (int k = 0; k < sb::kCoordinates; ++k) loc.dofs[k] = elementDof(el, k);
  return loc;
}

SpatialStrains SpatialAncfBeam::sectionStrains(const SpatialLocation &loc, const double *values) const
{
  const sb::Strains e = sb::strainsAt(geometry_, Eigen::Map<const sb::Vec14>(values), loc.xi);
  return {e.axial, e.torsion, e.curvature2, e.curvature3};
}

void SpatialAncfBeam::sample(const SpatialLocation &loc, double s, const double *values, SpatialSample &out) const
{
  const sb::Vec14 e = Eigen::Map<const sb::Vec14>(values);
  const sb::SectionFrame f = sb::sectionFrame(geometry_, e, (s - loc.begin) / geometry_.l);
  out.r = f.r;
  out.triad = f.d;
  out.r_q.setZero();
  out.r_q.leftCols<sb::kCoordinates>() = f.rGrad;
  for (int k = 0; k < 3; ++k) {
    out.d_q[k].setZero();
    out.d_q[k].leftCols<sb::kCoordinates>() = f.dGrad[k];
  }
}

void SpatialAncfBeam::curvatureTerm(const SpatialLocation &loc, double s, const double *values, SpatialField field,
                                    const Vec3 &w, SpatialHessian &H) const
{
  H.setZero();
  // The centreline is linear in the coordinates.
  if (field == SpatialField::Position) return;
  const sb::Vec14 e = Eigen::Map<const sb::Vec14>(values);
  H.topLeftCorner<sb::kCoordinates, sb::kCoordinates>() =
      sb::sectionFrameHessian(geometry_, e, (s - loc.begin) / geometry_.l, static_cast<int>(field) - 1, w);
}

namespace {

// The smallest rotation from a node's reference tangent to its current
// tangent is singular at half a turn and the triad is undefined at a zero
// slope: beyond about 170 degrees (cos < kTurnLimit), or at a slope shorter
// than a millionth of the reference one, the element is outside the chart
// of its fixed references and its residual is NaN (Newton reports a domain
// error and the step is cut).
constexpr double kTurnLimit = -0.985;

bool insideChart(const sb::Geometry &geo, const sb::Vec14 &e)
{
  for (int a = 0; a < 2; ++a) {
    const Vec3 slope = e.segment<3>(sb::slopeIndex(a));
    const double n = slope.norm();
    if (!(n > 1e-6) || !(slope.dot(geo.node[a].tangent) > kTurnLimit * n)) return false;
  }
  return true;
}

} // namespace

SpatialBeamElementItem::SpatialBeamElementItem(const SpatialAncfBeam &beam, int element,
                                               std::shared_ptr<const sb::Mat14> mass, const Vec3 &gravity)
  : beam_(&beam), element_(element), mass_(std::move(mass)),
    gravity_(sb::gravityForce(beam.section(), beam.elementLength(), gravity))
{
}

std::string SpatialBeamElementItem::name() const { return beam_->name() + ".element" + std::to_string(element_); }

void SpatialBeamElementItem::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.resize(sb::kCoordinates);
  for (int k = 0; k < sb::kCoordinates; ++k) dofs[k] = beam_->elementDof(element_, k);
}

void SpatialBeamElementItem::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual,
                                      double *J) const
{
  const Eigen::Map<const sb::Vec14> q(in.q), v(in.v), a(in.a);
  Eigen::Map<sb::Vec14> r(residual);
  const sb::Section &sec = beam_->section();
  const sb::Geometry &geo = beam_->geometry();
  if (!insideChart(geo, q)) {
    r.setConstant(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  const Kinematics &kin = ctx.kin;
  const bool wantK = J && kin.cQ != 0.0, wantV = J && kin.cV != 0.0;
  sb::Vec14 f, fd = sb::Vec14::Zero();
  sb::Mat14 K, Kq, Dv;
  if (sec.damped())
    sb::internalAndDampingForce(sec, geo, q, v, f, wantK ? &K : nullptr, fd, wantK ? &Kq : nullptr,
                                wantV ? &Dv : nullptr);
  else
    sb::internalForce(sec, geo, q, f, wantK ? &K : nullptr);
  r += (*mass_) * a + f + fd - ctx.loadFactor * gravity_;
  if (!J) return;
  Eigen::Map<Eigen::Matrix<double, sb::kCoordinates, sb::kCoordinates, Eigen::RowMajor>> Jm(J);
  Jm += kin.cA * (*mass_);
  if (wantK) {
    Jm += kin.cQ * K;
    if (sec.damped()) Jm += kin.cQ * Kq;
  }
  if (wantV && sec.damped()) Jm += kin.cV * Dv;
}

void SpatialBeamElementItem::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  const Eigen::Map<const sb::Vec14> q(in.q), v(in.v);
  e.kinetic += 0.5 * v.dot((*mass_) * v);
  const sb::Section &sec = beam_->section();
  const double u = sb::strainEnergy(sec, beam_->geometry(), q);
  e.strain += u;
  if (sec.damped()) {
    sb::Vec14 fd;
    e.dissipation += sb::dampingForce(sec, beam_->geometry(), q, v, fd, nullptr, nullptr);
  }
  // Round-off of the strains, as in the planar element: curvature and
  // torsion eps |q| / l^2, axial strain eps |q| / l.
  const double l = beam_->elementLength(), eps = std::numeric_limits<double>::epsilon();
  const double size = q.cwiseAbs().maxCoeff(), dk = eps * size / (l * l), de = eps * size / l;
  const double EI = std::max({sec.EIy, sec.EIz, sec.GJ});
  e.roundoff += 2.0 * std::sqrt(2.0 * std::abs(u) * l) * (std::sqrt(EI) * dk + std::sqrt(sec.EA) * de) +
                l * (EI * dk * dk + sec.EA * de * de);
  e.potential -= ctx.loadFactor * gravity_.dot(q);
}

bool SpatialBeamElementItem::dampingForce(const ItemValues &in, double *f) const
{
  const sb::Section &sec = beam_->section();
  if (!sec.damped()) return false;
  sb::Vec14 fd;
  sb::dampingForce(sec, beam_->geometry(), Eigen::Map<const sb::Vec14>(in.q), Eigen::Map<const sb::Vec14>(in.v), fd,
                   nullptr, nullptr);
  Eigen::Map<sb::Vec14>{f} = fd;
  return true;
}

void SpatialBeamElementItem::scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const
{
  sb::Vec14 f;
  sb::Mat14 K;
  sb::internalForce(beam_->section(), beam_->geometry(), Eigen::Map<const sb::Vec14>(in.q), f, &K);
  // Position entries only: slope and twist entries carry other units.
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 3; ++c) {
      const int k = sb::positionIndex(a) + c;
      massDiag += (*mass_)(k, k);
      stiffDiag += K(k, k);
    }
  count += 6;
}

} // namespace boomdyn
