#include "boomdyn/model.hpp"

#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/angle_drive.hpp"
#include "boomdyn/beam_element_item.hpp"
#include "boomdyn/lugre_friction.hpp"
#include "boomdyn/pin.hpp"
#include "boomdyn/rigid_body.hpp"
#include "boomdyn/rope.hpp"
#include "boomdyn/slack_drive.hpp"
#include "boomdyn/sliding_joint.hpp"
#include "boomdyn/spring.hpp"
#include "boomdyn/point_load.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>

namespace boomdyn {

namespace {

std::string where(const SourceMark &m)
{
  std::ostringstream os;
  os << m.file << ":" << m.line << ": key '" << m.key << "': ";
  return os.str();
}

Vec2 toVec(const Vec2d &v) { return Vec2(v[0], v[1]); }

// Largest omega^2 of one straight, unstrained element: K v = omega^2 M v.
double elementOmegaMax2(const ancf::Section &sec, double l)
{
  const ancf::Vec8 e = ancf::straightElement(Vec2::Zero(), Vec2(1, 0), l);
  ancf::Vec8 f;
  ancf::Mat8 K;
  ancf::internalForce(sec, l, e, f, &K);
  const Eigen::GeneralizedSelfAdjointEigenSolver<ancf::Mat8> eig(0.5 * (K + K.transpose()), ancf::massMatrix(sec.rhoA, l),
                                                                  Eigen::EigenvaluesOnly);
  return eig.eigenvalues().maxCoeff();
}

} // namespace

Model::Model(const Scene &scene) : scene_(scene)
{
  const Vec2 g = toVec(scene.gravity);
  for (const BodySpec &b : scene.bodies) {
    if (b.type == BodySpec::Type::Rigid) {
      // Mass from the section's mass per length; EA and EI play no part.
      auto rigid = std::make_unique<RigidBody>(b.name, b.length, b.section.rhoA * b.length, toVec(b.origin), b.angle, nq_);
      nq_ += rigid->numCoordinates();
      items_.push_back(std::make_unique<RigidBodyItem>(*rigid, g));
      bodies_.push_back(std::move(rigid));
      continue;
    }
    const ancf::Section sec{b.section.EA, b.section.EI, b.section.rhoA};
    auto beam = std::make_unique<AncfBeam>(b.name, b.length, b.elements, sec, toVec(b.origin), b.angle, nq_);
    nq_ += beam->numCoordinates();
    auto mass = std::make_shared<const ancf::Mat8>(ancf::massMatrix(sec.rhoA, beam->elementLength()));
    for (int el = 0; el < beam->numElements(); ++el) items_.push_back(std::make_unique<BeamElementItem>(*beam, el, mass, g));
    bodies_.push_back(std::move(beam));
  }
  // Slack coordinates follow the body coordinates, one per sliding joint,
  // starting where the slider point projects onto the (straight) initial track.
  std::vector<PetscInt> slackOf(scene.constraints.size(), -1);
  std::vector<double> s0Of(scene.constraints.size(), 0.0);
  std::vector<double> q0 = initialCoordinates();
  for (std::size_t k = 0; k < scene.constraints.size(); ++k) {
    const ConstraintSpec &c = scene.constraints[k];
    if (c.type != ConstraintSpec::Type::SlidingJoint) continue;
    const Body *track = findBody(c.track), *slider = findBody(c.a.body);
    CenterlineSample origin, point;
    const CenterlineLocation l0 = track->locate(0.0), lp = slider->locate(c.a.s);
    std::vector<double> v0(8), vp(8);
    for (int i = 0; i < 8; ++i) v0[i] = q0[l0.dofs[i]], vp[i] = q0[lp.dofs[i]];
    track->sample(l0, 0.0, v0.data(), origin);
    slider->sample(lp, c.a.s, vp.data(), point);
    const double s0 = (point.r[0] - origin.r[0]).dot(origin.r[1].normalized());
    if (s0 < 0.0 || s0 > track->length()) {
      std::ostringstream os;
      os << where(c.mark) << "sliding joint '" << c.name << "': the slider point lies outside its track '" << c.track
         << "' (at s = " << s0 << " m of " << track->length() << " m)";
      throw ModelError(os.str());
    }
    slackOf[k] = nq_++;
    s0Of[k] = s0;
    slackInitial_.push_back({slackOf[k], s0});
  }
  // One first-order friction state z per frictional sliding joint, after the
  // slack coordinates (so that every coordinate is numbered before the rows).
  std::vector<PetscInt> frictionStateOf(scene.constraints.size(), -1);
  for (std::size_t k = 0; k < scene.constraints.size(); ++k)
    if (scene.constraints[k].type == ConstraintSpec::Type::SlidingJoint && scene.constraints[k].friction) {
      frictionStateOf[k] = nq_++;
      firstOrder_.push_back(frictionStateOf[k]);
      frictionJoints_.push_back(scene.constraints[k].name);
    }
  for (std::size_t k = 0; k < scene.constraints.size(); ++k) {
    const ConstraintSpec &c = scene.constraints[k];
    const Body *a = c.type == ConstraintSpec::Type::ExtractionDrive ? nullptr : findBody(c.a.body);
    switch (c.type) {
    case ConstraintSpec::Type::ExtractionDrive: {
      std::size_t j = 0;
      while (j < scene.constraints.size() && !(scene.constraints[j].type == ConstraintSpec::Type::SlidingJoint &&
                                                scene.constraints[j].name == c.joint))
        ++j;
      if (j == scene.constraints.size())
        throw ModelError(where(c.mark) + "extraction drive '" + c.name + "': no sliding joint named '" + c.joint + "'");
      addConstraint(std::make_shared<SlackDrive>(c.name, slackOf[j], s0Of[j], c.displacement), c.mark);
      break;
    }
    case ConstraintSpec::Type::Rope: {
      const Rope::Point P{a, c.a.s}, Q{findBody(c.b->body), c.b->s}, R{findBody(c.c->body), c.c->s};
      double length = c.length;
      if (length <= 0) { // the rope is taut in the initial configuration
        const Rope probe(c.name, P, Q, R, 0.0);
        std::vector<PetscInt> dofs;
        probe.coordinates(dofs);
        std::vector<double> vals;
        for (PetscInt d : dofs) vals.push_back(q0[d]);
        length = probe.spannedLength(vals.data());
      }
      addConstraint(std::make_shared<Rope>(c.name, P, Q, R, length), c.mark);
      break;
    }
    case ConstraintSpec::Type::SlidingJoint: {
      auto joint = std::make_shared<SlidingJoint>(c.name, *findBody(c.track), *a, c.a.s, slackOf[k], s0Of[k]);
      slidingJoints_.push_back(joint);
      addConstraint(joint, c.mark);
      if (c.friction) { // lambda_n is the joint's second row
        auto friction = std::make_unique<LuGreFriction>(joint, frictionStateOf[k], constraints_.back()->firstRow() + 1,
                                                        *c.friction);
        frictions_.push_back(friction.get());
        items_.push_back(std::move(friction));
      }
      break;
    }
    case ConstraintSpec::Type::Pin:
      if (c.b) addConstraint(std::make_shared<Pin>(c.name, *a, c.a.s, *findBody(c.b->body), c.b->s), c.mark);
      else addConstraint(std::make_shared<Pin>(c.name, *a, c.a.s, toVec(c.ground)), c.mark);
      break;
    case ConstraintSpec::Type::AngleDrive:
      addConstraint(std::make_shared<AngleDrive>(c.name, *a, c.a.s, c.angle), c.mark);
      break;
    case ConstraintSpec::Type::Clamp:
      addConstraint(std::make_shared<Pin>(c.name + ".pin", *a, c.a.s, toVec(c.ground)), c.mark);
      addConstraint(std::make_shared<AngleDrive>(c.name + ".angle", *a, c.a.s, c.angle), c.mark);
      break;
    }
  }
  for (const PointForceSpec &f : scene.forces)
    items_.push_back(std::make_unique<PointForce>(f.name, *findBody(f.at.body), f.at.s, toVec(f.force), f.scale));
  for (const PointMassSpec &m : scene.masses) {
    // PointMass uses the linear centerline of ANCF beams (no centripetal term).
    if (dynamic_cast<const RigidBody *>(findBody(m.at.body)))
      throw ModelError(where(m.mark) + "point mass '" + m.name + "' on rigid body '" + m.at.body +
                       "': not supported; add its mass to the body's section instead");
    items_.push_back(std::make_unique<PointMass>(m.name, *findBody(m.at.body), m.at.s, m.mass, g));
  }
  for (const SpringSpec &sp : scene.springs) {
    Spring::End a{findBody(sp.a.body), sp.a.s, Vec2::Zero()}, b{nullptr, 0.0, toVec(sp.ground)};
    if (sp.b) b = Spring::End{findBody(sp.b->body), sp.b->s, Vec2::Zero()};
    double rest = sp.restLength;
    if (rest < 0) { // the initial distance
      const Spring probe(sp.name, a, b, 1.0, 0.0, 0.0);
      std::vector<PetscInt> dofs;
      probe.coordinates(dofs);
      std::vector<double> vals, zero(dofs.size(), 0.0);
      for (PetscInt d : dofs) vals.push_back(q0[d]);
      EnergyParts e;
      probe.energy(AssemblyContext{}, ItemValues{vals.data(), zero.data(), zero.data(), nullptr}, e);
      rest = std::sqrt(2.0 * e.strain); // with k = 1 and L0 = 0 the energy is l^2 / 2
    }
    items_.push_back(std::make_unique<Spring>(sp.name, a, b, sp.stiffness, rest, sp.damping));
  }
  for (const SensorSpec &s : scene.output.sensors) sensors_.push_back({s.name, findBody(s.at.body), s.at.s});
  checkInitialConfiguration();
}

void Model::addConstraint(std::shared_ptr<Constraint> c, const SourceMark &mark)
{
  // Multiplier rows follow all coordinates; bodies are created first, so nq_ is final here.
  const int rows = c->numRows();
  auto item = std::make_unique<ConstraintItem>(std::move(c), nq_ + nlambda_);
  nlambda_ += rows;
  constraints_.push_back(item.get());
  constraintMarks_.push_back(mark);
  items_.push_back(std::move(item));
}

const Body *Model::findBody(const std::string &name) const
{
  for (const auto &b : bodies_)
    if (b->name() == name) return b.get();
  throw ModelError("no body named '" + name + "'");
}

std::vector<double> Model::initialCoordinates() const
{
  std::vector<double> q(nq_);
  for (const auto &b : bodies_) b->initialCoordinates(q.data() + b->firstCoordinate());
  for (const auto &[index, s0] : slackInitial_) q[index] = s0;
  return q;
}

std::vector<Model::Conditioning> Model::iterationConditioning() const
{
  std::vector<Conditioning> out;
  if (scene_.analysis != Scene::Analysis::Dynamic) return out;
  // Generalized-alpha's beta for rho_inf (Chung & Hulbert), and the factor
  // (1 - alpha_f) / (1 - alpha_m) between K and the mass term's coefficient.
  const double rho = scene_.dynamic.rho_inf, am = (2 * rho - 1) / (rho + 1), af = rho / (rho + 1);
  const double beta = 0.25 * (1 - am + af) * (1 - am + af), c = beta * (1 - af) / (1 - am), h = scene_.dynamic.dt;
  for (const auto &b : bodies_) {
    const auto *beam = dynamic_cast<const AncfBeam *>(b.get());
    if (!beam) continue;
    Conditioning k;
    k.body = beam->name();
    k.elements = beam->numElements();
    k.elementLength = beam->elementLength();
    k.omegaMax = std::sqrt(elementOmegaMax2(beam->section(), k.elementLength));
    k.estimate = k.omegaMax * k.omegaMax * h * h * c;
    k.maxStep = std::sqrt(kIllConditioned / (k.omegaMax * k.omegaMax * c));
    // The estimate grows with the element count (like n^4 in bending): bisect.
    auto estimate = [&](int n) { return elementOmegaMax2(beam->section(), beam->length() / n) * h * h * c; };
    int lo = 1, hi = k.elements;
    if (estimate(hi) <= kIllConditioned) lo = hi;
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      (estimate(mid) <= kIllConditioned ? lo : hi) = mid;
    }
    k.maxElements = estimate(lo) <= kIllConditioned ? lo : 0;
    out.push_back(k);
  }
  return out;
}

std::vector<std::string> Model::conditioningWarnings() const
{
  std::vector<std::string> out;
  for (const Conditioning &k : iterationConditioning()) {
    if (k.estimate <= kIllConditioned) continue;
    std::ostringstream os;
    os.precision(3);
    os << scene_.file << ": body '" << k.body << "': " << k.elements << " elements of " << k.elementLength
       << " m with h = " << scene_.dynamic.dt << " s make the Newton iteration matrix M/(beta h^2) + K ill-conditioned "
       << "in double precision ((omega_max h)^2 beta = " << k.estimate << " > " << kIllConditioned
       << ", omega_max = " << k.omegaMax << " rad/s from EI, rhoA and the element length): Newton stagnates, steps are "
       << "rejected down to dt_min or accepted inaccurately. Use at most " << k.maxElements
       << " elements on this body at this h, or h <= " << k.maxStep << " s";
    out.push_back(os.str());
  }
  return out;
}

void Model::checkInitialConfiguration() const
{
  const std::vector<double> q = initialCoordinates();
  for (std::size_t k = 0; k < constraints_.size(); ++k) {
    const Constraint &c = constraints_[k]->constraint();
    std::vector<PetscInt> dofs;
    c.coordinates(dofs);
    std::vector<double> vals(dofs.size());
    for (std::size_t i = 0; i < dofs.size(); ++i) vals[i] = q[dofs[i]];
    ConstraintEval ev;
    c.evaluate(0.0, vals.data(), nullptr, nullptr, ev);
    for (int r = 0; r < c.numRows(); ++r)
      if (std::abs(ev.C[r]) > 1e-9) {
        std::ostringstream os;
        os << where(constraintMarks_[k]) << "constraint '" << c.name() << "' is violated by the initial configuration ("
           << "row " << r << ": " << ev.C[r] << " " << c.rowUnit(r)
           << "); place the bodies (origin, angle) so that it holds at t = 0";
        throw ModelError(os.str());
      }
  }
}

} // namespace boomdyn
