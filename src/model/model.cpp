#include "boomdyn/model.hpp"

#include "boomdyn/lugre_friction.hpp"
#include "boomdyn/pad_contact.hpp"
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

#include <algorithm>
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

} // namespace

Model::Model(const Scene &scene) : scene_(scene)
{
  // Bodies first, in scene order, each by its body type (physics_type.hpp):
  // their coordinates come first.
  BodyBuilder bodies(*this);
  for (const BodySpec &b : scene.bodies) bodyType(b.type).buildBody(b, bodies);
  // Everything else is built by its physics type (physics_type.hpp), stage
  // by stage over all components, so that the unknowns are numbered
  // [body coordinates | extra coordinates | first-order states | multiplier
  // rows] and each group in scene order.
  ModelBuilder builder(*this);
  using Stage = void (*PhysicsType::*)(const ComponentSpec &, ModelBuilder &);
  for (const Stage stage : {&PhysicsType::addCoordinates, &PhysicsType::addStates, &PhysicsType::build}) {
    // The bodies' own constraints get the first multiplier rows.
    if (stage == &PhysicsType::build)
      for (auto &[constraint, mark] : bodyConstraints_) builder.addConstraint(constraint, mark);
    for (const std::string &section : Scene::componentSections())
      for (ComponentSpec &spec : scene_.components(section)) {
        const PhysicsType *type = findPhysicsType(section, spec.type, scene_.dimension);
        if (!type) throw ModelError(where(spec.mark) + "no type '" + spec.type + "' in section " + section);
        if (stage == &PhysicsType::addCoordinates && type->complete) type->complete(spec, scene_);
        if (type->*stage) (type->*stage)(spec, builder);
      }
  }
  checkInitialConfiguration();
}

PetscInt ModelBuilder::addCoordinate(double initial)
{
  const PetscInt index = model_.nq_++;
  model_.slackInitial_.push_back({index, initial});
  return index;
}

PetscInt ModelBuilder::addFirstOrderState(const std::string &joint)
{
  const PetscInt index = addFirstOrderState("LuGre z of sliding_joint '" + joint + "'", 0.0, 0.0);
  model_.frictionJoints_.push_back(joint);
  return index;
}

PetscInt ModelBuilder::addFirstOrderState(const std::string &what, double initial, double floor)
{
  const PetscInt index = model_.nq_++;
  model_.firstOrder_.push_back(index);
  model_.firstOrderNames_.push_back(what);
  model_.firstOrderFloor_.push_back(floor);
  if (initial != 0) model_.slackInitial_.push_back({index, initial});
  return index;
}

const ConstraintItem &ModelBuilder::addConstraint(std::shared_ptr<Constraint> c, const SourceMark &mark)
{
  // Multiplier rows follow all coordinates, which are numbered in the earlier stages.
  const int rows = c->numRows();
  auto item = std::make_unique<ConstraintItem>(std::move(c), model_.nq_ + model_.nlambda_);
  model_.nlambda_ += rows;
  const ConstraintItem &added = *item;
  model_.constraints_.push_back(item.get());
  model_.constraintMarks_.push_back(mark);
  model_.items_.push_back(std::move(item));
  return added;
}

void ModelBuilder::addFriction(std::unique_ptr<LuGreFriction> friction)
{
  model_.frictions_.push_back(friction.get());
  model_.items_.push_back(std::move(friction));
}

const PadContact *ModelBuilder::addPad(std::unique_ptr<PadContact> pad)
{
  const PadContact *added = pad.get();
  model_.pads_.push_back(added);
  model_.items_.push_back(std::move(pad));
  return added;
}

const BodyBase *Model::findBody(const std::string &name) const
{
  for (const auto &b : bodies_)
    if (b->name() == name) return b.get();
  throw ModelError("no body named '" + name + "'");
}

double Model::totalMass() const
{
  double mass = 0;
  for (const BodySpec &b : scene_.bodies) mass += b.type == BodySpec::Type::SpatialRigid ? b.mass : b.section.rhoA * b.length;
  for (const ComponentSpec &m : scene_.masses)
    if (m.has("mass")) mass += m.number("mass");
  return mass;
}

double Model::energyScale() const
{
  const double mass = totalMass();
  double lo[2] = {0, 0}, hi[2] = {0, 0}, longest = 0;
  bool first = true;
  if (scene_.dimension == 3) return spatialEnergyScale(mass);
  for (const BodySpec &b : scene_.bodies) {
    longest = std::max(longest, b.length);
    const double end[2] = {b.origin[0] + b.length * std::cos(b.angle), b.origin[1] + b.length * std::sin(b.angle)};
    for (int i = 0; i < 2; ++i) {
      const double a = std::min(b.origin[i], end[i]), z = std::max(b.origin[i], end[i]);
      lo[i] = first ? a : std::min(lo[i], a), hi[i] = first ? z : std::max(hi[i], z);
    }
    first = false;
  }
  const double L = std::max({std::hypot(hi[0] - lo[0], hi[1] - lo[1]), longest}),
               g = std::hypot(scene_.gravity[0], scene_.gravity[1]), T = scene_.dynamic.t_end;
  const double scale = mass * (g * L + (T > 0 ? (L / T) * (L / T) : 0.0));
  return std::isfinite(scale) ? scale : 0.0;
}

double Model::spatialEnergyScale(double mass) const
{
  // As energyScale, with the bodies' ends in space.
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, longest = 0;
  bool first = true;
  for (const BodySpec &b : scene_.bodies) {
    longest = std::max(longest, b.length);
    const double n = std::sqrt(b.axis[0] * b.axis[0] + b.axis[1] * b.axis[1] + b.axis[2] * b.axis[2]);
    for (int i = 0; i < 3; ++i) {
      const double end = b.origin3[i] + (n > 0 ? b.length * b.axis[i] / n : 0.0);
      const double a = std::min(b.origin3[i], end), z = std::max(b.origin3[i], end);
      lo[i] = first ? a : std::min(lo[i], a), hi[i] = first ? z : std::max(hi[i], z);
    }
    first = false;
  }
  const double L = std::max(std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2])),
                            longest);
  const auto &g = scene_.gravity3;
  const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]), T = scene_.dynamic.t_end;
  const double scale = mass * (gn * L + (T > 0 ? (L / T) * (L / T) : 0.0));
  return std::isfinite(scale) ? scale : 0.0;
}

std::vector<double> Model::initialCoordinates() const
{
  std::vector<double> q(nq_);
  for (const auto &b : bodies_) b->initialCoordinates(q.data() + b->firstCoordinate());
  for (const auto &[index, s0] : slackInitial_) q[index] = s0;
  return q;
}

std::vector<double> Model::initialVelocities() const
{
  std::vector<double> v(nq_, 0.0);
  for (const auto &b : bodies_) b->initialVelocities(v.data() + b->firstCoordinate());
  return v;
}

std::vector<Model::Conditioning> Model::iterationConditioning() const
{
  std::vector<Conditioning> out;
  if (scene_.analysis != Scene::Analysis::Dynamic) return out;
  // Generalized-alpha's beta for rho_inf (Chung & Hulbert), and the factor
  // (1 - alpha_f) / (1 - alpha_m) between K and the mass term's coefficient.
  const double rho = scene_.dynamic.rho_inf, am = (2 * rho - 1) / (rho + 1), af = rho / (rho + 1);
  const double beta = 0.25 * (1 - am + af) * (1 - am + af), c = beta * (1 - af) / (1 - am), h = scene_.dynamic.dt;
  for (const BodySpec &body : scene_.bodies) {
    const auto elementOmegaMax2 = bodyType(body.type).elementOmegaMax2;
    if (!elementOmegaMax2) continue; // no elastic modes
    Conditioning k;
    k.body = body.name;
    k.elements = body.elements;
    k.elementLength = body.length / body.elements;
    k.omegaMax = std::sqrt(elementOmegaMax2(body, k.elementLength));
    k.estimate = k.omegaMax * k.omegaMax * h * h * c;
    k.maxStep = std::sqrt(kIllConditioned / (k.omegaMax * k.omegaMax * c));
    // The estimate grows with the element count (like n^4 in bending): bisect.
    auto estimate = [&](int n) { return elementOmegaMax2(body, body.length / n) * h * h * c; };
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
  const std::vector<double> q = initialCoordinates(), v0 = initialVelocities();
  const bool moving = std::any_of(v0.begin(), v0.end(), [](double x) { return x != 0.0; });
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
    // Bodies given initial velocities: those must satisfy C_q v + C_t = 0
    // (a drive's C_t is projected at the start; the other rows are not).
    if (!moving || c.dependsOnTime()) continue;
    std::vector<double> vv(dofs.size());
    for (std::size_t i = 0; i < dofs.size(); ++i) vv[i] = v0[dofs[i]];
    const Eigen::VectorXd rate = ev.Cq * Eigen::Map<const Eigen::VectorXd>(vv.data(), static_cast<int>(vv.size()));
    for (int r = 0; r < c.numRows(); ++r)
      if (std::abs(rate[r]) > 1e-9) {
        std::ostringstream os;
        os << where(constraintMarks_[k]) << "constraint '" << c.name() << "' is violated by the initial velocities ("
           << "row " << r << ": dC/dt = " << rate[r] << " " << c.rowUnit(r)
           << "/s); give the bodies velocities the joints allow (velocity, angular_velocity)";
        throw ModelError(os.str());
      }
  }
}

} // namespace boomdyn
