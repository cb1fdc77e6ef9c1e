#include "boomdyn/spatial_ancf_beam.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace boomdyn {

namespace sb = spatial_beam;

SpatialAncfBeam::SpatialAncfBeam(std::string name, double length, int elements, const sb::Section &section,
                                 const Vec3 &origin, const Mat3 &triad, PetscInt first)
  : SpatialBody(std::move(name), length, first), elements_(elements), section_(section), origin_(origin),
    triad_(triad), l_(length / elements), frames_(elements + 1, sb::NodeFrame{triad.col(0), triad.col(1)})
{
}

std::vector<PetscInt> SpatialAncfBeam::slopeDofs() const
{
  std::vector<PetscInt> dofs;
  for (int n = 0; n <= elements_; ++n)
    for (int c = 0; c < 3; ++c) dofs.push_back(first_ + 7 * n + 3 + c);
  return dofs;
}

bool SpatialAncfBeam::rebase(const double *slopes, bool always)
{
  // All nodes together, so that the two references of an element always
  // come from the same state (their twist angle beta stays small).
  const double limit = std::cos(kRebaseAngle * M_PI / 180.0);
  bool far = always;
  for (int n = 0; n <= elements_ && !far; ++n) {
    const Eigen::Map<const Vec3> slope(slopes + 3 * n);
    far = slope.dot(frames_[n].tangent) < limit * slope.norm();
  }
  if (!far) return false;
  for (int n = 0; n <= elements_; ++n)
    frames_[n] = sb::rebasedNodeFrame(frames_[n], Eigen::Map<const Vec3>(slopes + 3 * n));
  return true;
}

std::vector<double> SpatialAncfBeam::references() const
{
  std::vector<double> values;
  for (const sb::NodeFrame &f : frames_) {
    values.insert(values.end(), f.tangent.data(), f.tangent.data() + 3);
    values.insert(values.end(), f.normal.data(), f.normal.data() + 3);
  }
  return values;
}

void SpatialAncfBeam::setReferences(const double *values)
{
  for (std::size_t n = 0; n < frames_.size(); ++n) {
    frames_[n].tangent = Eigen::Map<const Vec3>(values + 6 * n);
    frames_[n].normal = Eigen::Map<const Vec3>(values + 6 * n + 3);
  }
}

void SpatialAncfBeam::initialCoordinates(double *q) const
{
  const double l = l_;
  for (int n = 0; n <= elements_; ++n) {
    Eigen::Map<Vec3>(q + 7 * n) = origin_ + (n * l) * triad_.col(0);
    Eigen::Map<Vec3>(q + 7 * n + 3) = triad_.col(0);
    q[7 * n + 6] = 0.0;
  }
}

SpatialLocation SpatialAncfBeam::locate(double s) const
{
  const double l = l_;
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
  const sb::Strains e = sb::strainsAt(geometry(loc.element), Eigen::Map<const sb::Vec14>(values), loc.xi);
  return {e.axial, e.torsion, e.curvature2, e.curvature3};
}

void SpatialAncfBeam::sample(const SpatialLocation &loc, double s, const double *values, SpatialSample &out) const
{
  const sb::Vec14 e = Eigen::Map<const sb::Vec14>(values);
  const sb::SectionFrame f = sb::sectionFrame(geometry(loc.element), e, (s - loc.begin) / l_);
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
      sb::sectionFrameHessian(geometry(loc.element), e, (s - loc.begin) / l_, static_cast<int>(field) - 1, w);
}

namespace {

// The smallest rotation from a node's reference tangent to its current
// tangent is singular at half a turn and the triad is undefined at a zero
// slope: beyond about 170 degrees (cos < kTurnLimit) from the reference,
// which rebasing (SpatialAncfBeam::rebase) keeps within 120 degrees of the
// tangent at accepted states, or at a slope shorter than a millionth of the
// reference one, the element is outside the chart of its references and its
// residual is NaN (Newton reports a domain error and the step is cut).
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
  const sb::Geometry geo = beam_->geometry(element_);
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
  const double u = sb::strainEnergy(sec, beam_->geometry(element_), q);
  e.strain += u;
  if (sec.damped()) {
    sb::Vec14 fd;
    e.dissipation += sb::dampingForce(sec, beam_->geometry(element_), q, v, fd, nullptr, nullptr);
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
  sb::dampingForce(sec, beam_->geometry(element_), Eigen::Map<const sb::Vec14>(in.q), Eigen::Map<const sb::Vec14>(in.v), fd,
                   nullptr, nullptr);
  Eigen::Map<sb::Vec14>{f} = fd;
  return true;
}

void SpatialBeamElementItem::scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const
{
  sb::Vec14 f;
  sb::Mat14 K;
  sb::internalForce(beam_->section(), beam_->geometry(element_), Eigen::Map<const sb::Vec14>(in.q), f, &K);
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

namespace boomdyn {

void SpatialBeamElementItem::modeEnergy(const PencilPass &stiffness, int n, const double *shape, double *scratch,
                                        ModeEnergy &out) const
{
  // As the planar element (BeamElementItem::modeEnergy): the material part
  // of 1/2 s^T K s strain by strain as half the Kelvin-Voigt power of the
  // rate s with a unit retardation time on that strain alone (EIy or EIz
  // set to zero to separate the two curvatures), the rest geometric. In the
  // plane of the axis and `up` (d1, d2) the axis bends about d3 (K3, EIz):
  // in-plane; about d2 (K2, EIy): out of plane.
  ModeEnergy whole;
  WorkItem::modeEnergy(stiffness, n, shape, scratch, whole);
  const double total = whole.kind[static_cast<int>(ModeEnergyKind::Geometric)];
  const sb::Vec14 q = Eigen::Map<const sb::Vec14>(stiffness.in.q), s = Eigen::Map<const sb::Vec14>(shape);
  const sb::Geometry geo = beam_->geometry(element_);
  sb::Section axial = beam_->section();
  axial.etaA = 1, axial.etaB = 0, axial.etaT = 0;
  sb::Section torsion = axial, inPlane = axial, outOfPlane = axial;
  torsion.etaA = 0, torsion.etaT = 1;
  inPlane.etaA = 0, inPlane.etaB = 1, inPlane.EIy = 0;
  outOfPlane.etaA = 0, outOfPlane.etaB = 1, outOfPlane.EIz = 0;
  sb::Vec14 fd;
  const double parts[4] = {0.5 * sb::dampingForce(axial, geo, q, s, fd, nullptr, nullptr),
                           0.5 * sb::dampingForce(inPlane, geo, q, s, fd, nullptr, nullptr),
                           0.5 * sb::dampingForce(outOfPlane, geo, q, s, fd, nullptr, nullptr),
                           0.5 * sb::dampingForce(torsion, geo, q, s, fd, nullptr, nullptr)};
  out.add(ModeEnergyKind::Axial, parts[0]);
  out.add(ModeEnergyKind::BendingInPlane, parts[1]);
  out.add(ModeEnergyKind::BendingOutOfPlane, parts[2]);
  out.add(ModeEnergyKind::Torsion, parts[3]);
  out.add(ModeEnergyKind::Geometric, total - parts[0] - parts[1] - parts[2] - parts[3]);
}

} // namespace boomdyn
