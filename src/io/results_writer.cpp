#include "boomdyn/results_writer.hpp"

#include "boomdyn/spatial_body.hpp"

#include "boomdyn/gather.hpp"

#include "boomdyn/log_events.hpp"
#include "xdmf_text.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <stdexcept>

namespace boomdyn {

// Names of the event sources' components and the union of their kinds, in
// first-seen order: /type_events stores indices into these two lists.
static std::vector<std::string> eventComponents(const Model &model)
{
  std::vector<std::string> names;
  for (const EventSource &e : model.eventSources())
    if (std::find(names.begin(), names.end(), e.component) == names.end()) names.push_back(e.component);
  return names;
}

static std::vector<std::string> eventKinds(const Model &model)
{
  std::vector<std::string> kinds;
  for (const EventSource &e : model.eventSources())
    for (const std::string &k : e.kinds)
      if (std::find(kinds.begin(), kinds.end(), k) == kinds.end()) kinds.push_back(k);
  return kinds;
}

namespace {

const char *analysisName(Scene::Analysis a)
{
  switch (a) {
  case Scene::Analysis::Static: return "static";
  case Scene::Analysis::Dynamic: return "dynamic";
  case Scene::Analysis::Modal: return "modal";
  }
  return "unknown";
}

std::string utcNow()
{
  const std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return buf;
}

} // namespace

// The per-step series' paths, made once: a literal passed as a
// std::string was a new string per row (on the heap for the longer names).
namespace {
const std::string kStepTime = "/steps/time", kStepDt = "/steps/dt", kStepIterations = "/steps/newton_iterations",
                  kStepViolation = "/steps/constraint_violation", kStepEnergy = "/steps/energy",
                  kStepSlack = "/steps/slack", kStepLambda = "/steps/lambda", kStepRopeTension = "/steps/rope_tension",
                  kStepFrameDeflection = "/steps/frame_deflection", kStepOutputs = "/steps/outputs";
} // namespace

namespace {
const char *const kRunningStatus = "running: the run had not ended when this was written (killed?)";
} // namespace

ResultsWriter::~ResultsWriter()
{
  // Left without finish() (an error unwound the run): the rows written so far
  // stay, and the summary says the run did not complete.
  if (file_ && file_->isOpen()) {
    try {
      file_->setAttribute("/summary", "status", std::string("failed: stopped by an error (see the program's output)"));
      if (!snapshotTimes_.empty()) writeXdmf();
      file_->close();
    } catch (...) {
    }
  }
}

PetscErrorCode ResultsWriter::open(const std::string &path, bool overwrite, const RunInfo &info, Vec layout)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  path_ = path;
  PetscCall(VecScatterCreateToZero(layout, toZero_.address(), gathered_.address()));
  // Rank 0 creates the file; every rank learns whether that worked, so all stop together.
  int ok = 1;
  std::string error;
  if (rank_ == 0) {
    try {
      file_ = std::make_unique<Hdf5File>(path, overwrite);
      const Scene &sc = model_.scene();
      file_->setAttribute("/", "boomdyn_version", info.version);
      file_->setAttribute("/", "scene_name", sc.name);
      file_->setAttribute("/", "scene_file", sc.file);
      file_->setAttribute("/", "analysis", std::string(analysisName(sc.analysis)));
      file_->setAttribute("/", "command_line", info.commandLine);
      file_->setAttribute("/", "petsc_options", info.petscOptions);
      file_->setAttribute("/", "created_utc", utcNow());
      file_->setAttribute("/", "mpi_ranks", static_cast<long long>(info.ranks));
      // Replaced at the end (completed, failed: ..., interrupted); a file
      // that still says this was left by a run that was killed.
      file_->setAttribute("/summary", "status", std::string(kRunningStatus));
      file_->writeString("/scene/text", sc.text);
      file_->setAttribute("/layout", "nq", static_cast<long long>(model_.numCoordinates()));
      file_->setAttribute("/layout", "nlambda", static_cast<long long>(model_.numMultipliers()));
      file_->setAttribute("/layout", "dimension", static_cast<long long>(model_.scene().dimension));
      std::vector<std::string> names, cnames;
      std::vector<int> first, count, cfirst, crows;
      for (const auto &b : model_.bodies()) {
        names.push_back(b->name());
        first.push_back(static_cast<int>(b->firstCoordinate()));
        count.push_back(static_cast<int>(b->numCoordinates()));
      }
      for (const ConstraintItem *c : model_.constraints()) {
        cnames.push_back(c->name());
        cfirst.push_back(static_cast<int>(c->firstRow() - model_.numCoordinates()));
        crows.push_back(c->constraint().numRows());
      }
      file_->writeStrings("/layout/body_names", names);
      file_->writeArray("/layout/body_first_coordinate", first, {first.size()});
      file_->writeArray("/layout/body_num_coordinates", count, {count.size()});
      std::vector<std::string> joints;
      for (const auto &j : model_.slidingJoints()) joints.push_back(j->name());
      if (!joints.empty()) file_->writeStrings("/layout/sliding_joint_names", joints);
      std::vector<std::string> ropes;
      for (const OutputChannel &ch : model_.outputChannels())
        if (ch.group == "rope") ropes.push_back(ch.name);
      if (!ropes.empty()) file_->writeStrings("/layout/rope_names", ropes);
      // Every registered type's output channels, in the columns of /steps/outputs.
      std::vector<std::string> outputNames, outputUnits;
      for (const OutputChannel &ch : model_.outputChannels()) {
        outputNames.push_back(ch.group + "/" + ch.name + "/" + ch.quantity);
        outputUnits.push_back(ch.unit);
      }
      if (!outputNames.empty()) {
        file_->writeStrings("/layout/output_names", outputNames);
        file_->writeStrings("/layout/output_units", outputUnits);
      }
      if (!model_.frictionJointNames().empty())
        file_->writeStrings("/layout/friction_joint_names", model_.frictionJointNames());
      if (!model_.eventSources().empty()) { // /type_events/{component,kind} index these
        file_->writeStrings("/layout/type_event_components", eventComponents(model_));
        file_->writeStrings("/layout/type_event_kinds", eventKinds(model_));
      }
      std::vector<std::string> frames;
      for (const FrameSensor &f : model_.frameSensors())
        if (f.body) frames.push_back(f.name); // the columns of /steps/frame_deflection (planar scenes)
      if (!frames.empty()) file_->writeStrings("/layout/frame_names", frames);
      if (!cnames.empty()) {
        file_->writeStrings("/layout/constraint_names", cnames);
        file_->writeArray("/layout/constraint_first_row", cfirst, {cfirst.size()});
        file_->writeArray("/layout/constraint_num_rows", crows, {crows.size()});
      }
      file_->flush();
    } catch (const std::exception &e) {
      ok = 0;
      error = e.what();
      try { // a file that was created says why it has no results
        if (file_ && file_->isOpen()) file_->setAttribute("/summary", "status", "failed: " + error), file_->close();
      } catch (...) {
      }
      file_.reset();
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm_));
  if (!ok) {
    // A user error (existing file, unwritable folder): every rank throws the same message.
    char message[512] = "";
    if (rank_ == 0) PetscCall(PetscStrncpy(message, error.c_str(), sizeof message));
    PetscCallMPI(MPI_Bcast(message, sizeof message, MPI_CHAR, 0, comm_));
    throw std::runtime_error(std::string("results file: ") + message);
  }
  PetscFunctionReturn(0);
}

// Runs a rank-0 file operation; a failure there (disk full, ...) becomes a
// PETSc error on every rank instead of an exception on one and a hang on the rest.
template <class F>
static PetscErrorCode onRankZero(MPI_Comm comm, int rank, F &&op)
{
  int ok = 1;
  char message[512] = "";
  PetscFunctionBeginUser;
  if (rank == 0) {
    try {
      op();
    } catch (const std::exception &e) {
      ok = 0;
      PetscCall(PetscStrncpy(message, e.what(), sizeof message));
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  if (!ok) PetscCallMPI(MPI_Bcast(message, sizeof message, MPI_CHAR, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_WRITE, "writing results: %s", message);
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsWriter::appendStep(double t, double dt, PetscInt iterations, double violation,
                                         const EnergyParts &e, const std::vector<SensorReading> &sensors)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().output, 0, 0, 0, 0));
  PetscCall(onRankZero(comm_, rank_, [&] { appendStepRow(t, dt, iterations, violation, e, sensors); }));
  PetscCall(PetscLogEventEnd(logEvents().output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsWriter::appendJoints(const std::vector<double> &slacks, const std::vector<double> &multipliers,
                                           const std::vector<double> &ropeTensions,
                                           const std::vector<double> &frameDeflections,
                                           const std::vector<double> &outputs)
{
  PetscFunctionBeginUser;
  PetscCall(onRankZero(comm_, rank_, [&] {
    if (!slacks.empty()) file_->appendRow(kStepSlack, slacks.data(), slacks.size());
    if (!multipliers.empty()) file_->appendRow(kStepLambda, multipliers.data(), multipliers.size());
    if (!ropeTensions.empty()) file_->appendRow(kStepRopeTension, ropeTensions.data(), ropeTensions.size());
    if (!frameDeflections.empty())
      file_->appendRow(kStepFrameDeflection, frameDeflections.data(), frameDeflections.size());
    if (!outputs.empty()) file_->appendRow(kStepOutputs, outputs.data(), outputs.size());
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsWriter::appendSections(const std::vector<SectionReading> &sections)
{
  PetscFunctionBeginUser;
  PetscCall(onRankZero(comm_, rank_, [&] {
    if (sectionPaths_.size() != 4 * sections.size()) {
      sectionPaths_.clear();
      for (const FrameSensor &f : model_.frameSensors())
        if (f.spatialBody)
          for (const char *part : {"/triad", "/twist", "/angular_velocity", "/strains"})
            sectionPaths_.push_back("/frames/" + f.name + part);
    }
    for (std::size_t i = 0; i < sections.size(); ++i) {
      const SectionReading &r = sections[i];
      // Row-major: entry 3 i + j is component i of director d_(j+1).
      const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> triad = r.triad;
      const double strains[4] = {r.strains.axial, r.strains.torsion, r.strains.curvature2, r.strains.curvature3};
      file_->appendRow(sectionPaths_[4 * i], triad.data(), 9);
      file_->appendScalar(sectionPaths_[4 * i + 1], r.twist);
      file_->appendRow(sectionPaths_[4 * i + 2], r.angularVelocity.data(), 3);
      file_->appendRow(sectionPaths_[4 * i + 3], strains, 4);
    }
  }));
  PetscFunctionReturn(0);
}

void ResultsWriter::appendStepRow(double t, double dt, PetscInt iterations, double violation, const EnergyParts &e,
                                  const std::vector<SensorReading> &sensors)
{
  file_->appendScalar(kStepTime, t);
  file_->appendScalar(kStepDt, dt);
  file_->appendScalarInt(kStepIterations, static_cast<int>(iterations));
  file_->appendScalar(kStepViolation, violation);
  const double energy[4] = {e.kinetic, e.strain, e.potential, e.kinetic + e.strain + e.potential};
  file_->appendRow(kStepEnergy, energy, 4);
  if (sensorPaths_.size() != 2 * sensors.size()) {
    sensorPaths_.clear();
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      const std::string base = "/sensors/" + model_.sensors()[i].name;
      sensorPaths_.push_back(base + "/position");
      sensorPaths_.push_back(base + "/velocity");
    }
  }
  if (model_.scene().dimension == 3)
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      file_->appendRow(sensorPaths_[2 * i], sensors[i].position3.data(), 3);
      file_->appendRow(sensorPaths_[2 * i + 1], sensors[i].velocity3.data(), 3);
    }
  else
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      file_->appendRow(sensorPaths_[2 * i], sensors[i].position.data(), 2);
      file_->appendRow(sensorPaths_[2 * i + 1], sensors[i].velocity.data(), 2);
    }
  // Flush every couple of seconds so that a crash keeps the rows written so far.
  const auto now = std::chrono::steady_clock::now();
  if (now - lastFlush_ > std::chrono::seconds(2)) {
    file_->flush();
    lastFlush_ = now;
  }
}

PetscErrorCode ResultsWriter::gather(Vec v, std::vector<double> &out)
{
  PetscFunctionBeginUser;
  PetscCall(scatterValues(toZero_, v, gathered_, out));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsWriter::appendState(double t, Vec q, Vec v, Vec lambda)
{
  std::vector<double> qa, va, la;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().output, 0, 0, 0, 0));
  PetscCall(gather(q, qa));
  PetscCall(gather(v, va));
  PetscCall(gather(lambda, la));
  PetscCall(onRankZero(comm_, rank_, [&] {
    const std::size_t nq = model_.numCoordinates(), nl = model_.numMultipliers();
    file_->appendScalar("/state/time", t);
    file_->appendRow("/state/q", qa.data(), nq);
    file_->appendRow("/state/v", va.data(), nq);
    if (nl > 0) file_->appendRow("/state/lambda", la.data() + nq, nl);
    writeSampledBooms(t, qa, va);
    // Flushed like the step rows, every couple of seconds and at the end:
    // a flush per snapshot also wrote out every buffered step series, and
    // was most of the output time of a run with snapshots every 10 steps.
    const auto now = std::chrono::steady_clock::now();
    if (snapshotTimes_.size() == 1 || now - lastFlush_ > std::chrono::seconds(2)) {
      file_->flush();
      lastFlush_ = now;
    }
    // The XDMF text grows with every snapshot: rewrite it now and then (and
    // always in finish()), not at every snapshot, which would be quadratic.
    if (snapshotTimes_.size() == 1 || now - lastXdmf_ > std::chrono::seconds(5)) {
      writeXdmf();
      lastXdmf_ = now;
    }
  }));
  PetscCall(PetscLogEventEnd(logEvents().output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// Points per element at which beams are sampled for ParaView (plus the end).
static constexpr int kSamplesPerElement = 4;

void ResultsWriter::writeSampledBooms(double t, const std::vector<double> &q, const std::vector<double> &v)
{
  std::vector<double> &points = samplePoints_, &velocity = sampleVelocity_, &strain = sampleStrain_,
                      &curvature = sampleCurvature_;
  std::vector<int> &segments = sampleSegments_;
  points.clear(), velocity.clear(), strain.clear(), curvature.clear(), segments.clear();
  sampleTwist_.clear(), sampleTorsion_.clear(), sampleD2_.clear(), sampleD3_.clear();
  for (const auto &base : model_.bodies()) {
    if (base->dimension() == 3) {
      writeSpatialBody(static_cast<const SpatialBody &>(*base), q, v);
      continue;
    }
    const Body *body = static_cast<const Body *>(base.get());
    const int n = body->outputSegments() + 1;
    const int first = static_cast<int>(points.size() / 3);
    for (int k = 0; k < n; ++k) {
      const double s = body->length() * k / (n - 1);
      const CenterlineLocation loc = body->locate(s);
      double vals[8], vels[8];
      for (int i = 0; i < loc.count; ++i) vals[i] = q[loc.dofs[i]], vels[i] = v[loc.dofs[i]];
      CenterlineSample p;
      body->sample(loc, s, vals, p);
      const Vec2 r1 = p.r[1], r2 = p.r[2];
      const Vec2 vel = p.r_q[0].leftCols(loc.count) * Eigen::Map<const Eigen::VectorXd>(vels, loc.count);
      points.push_back(p.r[0].x()), points.push_back(p.r[0].y()), points.push_back(0.0);
      velocity.push_back(vel.x()), velocity.push_back(vel.y()), velocity.push_back(0.0);
      strain.push_back(0.5 * (r1.squaredNorm() - 1.0));                             // Green axial strain
      curvature.push_back((r1.x() * r2.y() - r1.y() * r2.x()) / r1.squaredNorm()); // material curvature
      if (k > 0) segments.push_back(first + k - 1), segments.push_back(first + k);
    }
  }
  const std::size_t np = points.size() / 3, ns = segments.size() / 2;
  const std::string base = "/paraview/" + std::to_string(snapshotTimes_.size());
  if (snapshotTimes_.empty()) file_->writeArray("/paraview/segments", segments, {ns, 2});
  std::vector<Hdf5File::NamedArray> arrays = {
    {"points", &points, {np, 3}}, {"velocity", &velocity, {np, 3}}, {"axial_strain", &strain, {np}},
    {"curvature", &curvature, {np}}};
  if (model_.scene().dimension == 3) // the sections: twist, torsion and the directions d2, d3
    arrays.insert(arrays.end(), {{"twist", &sampleTwist_, {np}},
                                 {"torsion", &sampleTorsion_, {np}},
                                 {"d2", &sampleD2_, {np, 3}},
                                 {"d3", &sampleD3_, {np, 3}}});
  // The ropes as polylines through their pulleys (rope_polylines.hpp).
  std::vector<double> &ropePoints = sampleRopePoints_;
  std::vector<int> &ropeSegments = sampleRopeSegments_;
  ropePolylines(ropes_, q, ropePoints, ropeSegments);
  if (!ropeSegments.empty()) {
    if (snapshotTimes_.empty()) file_->writeArray("/paraview/rope_segments", ropeSegments, {ropeSegments.size() / 2, 2});
    arrays.push_back({"rope_points", &ropePoints, {ropePoints.size() / 3, 3}});
  }
  file_->writeGroup(base, arrays, "time", t);
  ropePoints_ = ropePoints.size() / 3, ropeSegments_ = ropeSegments.size() / 2;
  snapshotTimes_.push_back(t);
  sampledPoints_ = np, sampledSegments_ = ns;
}

// A spatial body sampled along its axis (outputSegments + 1 points): the
// points, their velocities and the section there (section_reading.hpp):
// axial strain, bending-curvature magnitude, torsion, twist, d2 and d3.
void ResultsWriter::writeSpatialBody(const SpatialBody &body, const std::vector<double> &q, const std::vector<double> &v)
{
  const int n = body.outputSegments() + 1, first = static_cast<int>(samplePoints_.size() / 3);
  for (int k = 0; k < n; ++k) {
    const double s = body.length() * k / (n - 1);
    const SpatialLocation loc = body.locate(s);
    double vals[kSpatialMaxDofs], vels[kSpatialMaxDofs];
    for (int i = 0; i < loc.count; ++i) vals[i] = q[loc.dofs[i]], vels[i] = v[loc.dofs[i]];
    const SectionReading r = readSection(body, loc, s, vals, vels);
    for (int i = 0; i < 3; ++i) {
      samplePoints_.push_back(r.position[i]), sampleVelocity_.push_back(r.velocity[i]);
      sampleD2_.push_back(r.triad(i, 1)), sampleD3_.push_back(r.triad(i, 2));
    }
    sampleStrain_.push_back(r.strains.axial);
    sampleCurvature_.push_back(std::hypot(r.strains.curvature2, r.strains.curvature3));
    sampleTorsion_.push_back(r.strains.torsion), sampleTwist_.push_back(r.twist);
    if (k > 0) sampleSegments_.push_back(first + k - 1), sampleSegments_.push_back(first + k);
  }
}

void ResultsWriter::writeXdmf() const
{
  // Beside the results file, same stem; HDF5 paths are relative to the XDMF file.
  const std::string xmf = (path_.size() > 3 && path_.compare(path_.size() - 3, 3, ".h5") == 0 ? path_.substr(0, path_.size() - 3) : path_) + ".xmf";
  const std::string h5 = path_.substr(path_.find_last_of('/') == std::string::npos ? 0 : path_.find_last_of('/') + 1);
  const std::string np = std::to_string(sampledPoints_);
  const bool spatial = model_.scene().dimension == 3;
  // The grids of the snapshots described before are kept: only the new ones
  // are formed (the whole text at every rewrite grew with the snapshots).
  const std::array<std::size_t, 4> shape = {sampledPoints_, sampledSegments_, ropePoints_, ropeSegments_};
  if (shape != xdmfShape_) xdmfBooms_.clear(), xdmfRopes_.clear(), xdmfGrids_ = 0, xdmfShape_ = shape;
  for (std::size_t k = xdmfGrids_; k < snapshotTimes_.size(); ++k) {
    const std::string g = h5 + ":/paraview/" + std::to_string(k);
    std::string &text = xdmfBooms_;
    text += xdmf::polylineGridBegin("booms", snapshotTimes_[k], sampledSegments_, sampledPoints_,
                                    h5 + ":/paraview/segments", g + "/points");
    for (const char *field : {"axial_strain", "curvature"}) text += xdmf::nodeAttribute(field, false, np, g + "/" + field);
    text += xdmf::nodeAttribute("velocity", true, np, g + "/velocity");
    if (spatial) // docs/output.md: the section's twist and torsion, and its directions d2 and d3
      for (const char *field : {"twist", "torsion", "d2", "d3"})
        text += xdmf::nodeAttribute(field, field[0] == 'd', np, g + "/" + field);
    text += "   </Grid>\n";
    if (ropeSegments_ > 0) xdmfRopes_ += ropesXdmfGrid(h5, k, snapshotTimes_[k], ropePoints_, ropeSegments_);
  }
  xdmfGrids_ = snapshotTimes_.size();
  xdmf::writeFileReplacing(xmf, xdmf::collectionBegin(model_.scene().name) + xdmfBooms_ + xdmf::collectionEnd());
  if (ropeSegments_ > 0) writeRopesXdmf(xmf.substr(0, xmf.size() - 4) + ".ropes.xmf", model_.scene().name, xdmfRopes_);
}

PetscErrorCode ResultsWriter::writeModes(double t, const ModalResult &modes)
{
  PetscFunctionBeginUser;
  PetscCall(onRankZero(comm_, rank_, [&] { writeModeArrays(t, modes); }));
  PetscFunctionReturn(0);
}

void ResultsWriter::writeModeArrays(double t, const ModalResult &modes)
{
  const std::size_t k = modes.frequencyHz.size(), nq = model_.numCoordinates();
  file_->writeArray("/modal/frequencies_hz", modes.frequencyHz, {k});
  file_->writeArray("/modal/omega2", modes.omega2, {k});
  file_->writeArray("/modal/relative_residual", modes.residuals, {k});
  std::vector<double> shapes;
  for (const auto &s : modes.shapes) shapes.insert(shapes.end(), s.begin(), s.end());
  file_->writeArray("/modal/shapes", shapes, {k, nq});
  if (modes.energyShares.size() == k) { // the mode labels (docs/output.md)
    std::vector<double> shares;
    std::vector<std::string> labels;
    for (const EnergyShares &e : modes.energyShares)
      shares.insert(shares.end(), e.begin(), e.end()), labels.push_back(modeLabel(e));
    file_->writeArray("/modal/energy_shares", shares, {k, static_cast<std::size_t>(kModeEnergyKinds)});
    file_->writeStrings("/modal/energy_kinds", modeEnergyKindNames());
    file_->writeStrings("/modal/labels", labels);
  }
  if (!modes.dampingRatio.empty()) { // a damped model (docs/output.md)
    file_->writeArray("/modal/damped_frequencies_hz", modes.dampedFrequencyHz, {k});
    file_->writeArray("/modal/undamped_equivalent_hz", modes.undampedEquivalentHz, {k});
    file_->writeArray("/modal/damping_ratio", modes.dampingRatio, {k});
    file_->writeArray("/modal/decay_rates", modes.decayRates, {k, 2});
  }
  file_->setAttribute("/modal", "state_time", t);
  file_->flush();
}

PetscErrorCode ResultsWriter::appendFriction(const std::vector<FrictionReading> &readings)
{
  PetscFunctionBeginUser;
  PetscCall(onRankZero(comm_, rank_, [&] {
    if (readings.empty()) return;
    std::vector<double> v, vf, f, z;
    std::vector<int> st;
    for (const FrictionReading &r : readings)
      v.push_back(r.slipVelocity), vf.push_back(r.filteredSlipVelocity), f.push_back(r.force), z.push_back(r.z),
        st.push_back(r.slipping);
    file_->appendRow("/steps/friction_slip_velocity", v.data(), v.size());
    file_->appendRow("/steps/friction_slip_velocity_filtered", vf.data(), vf.size());
    file_->appendRow("/steps/friction_force", f.data(), f.size());
    file_->appendRow("/steps/friction_z", z.data(), z.size());
    file_->appendRow("/steps/friction_slipping", st.data(), st.size());
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsWriter::appendEvents(const std::vector<StickSlipEvent> &events)
{
  PetscFunctionBeginUser;
  PetscCall(onRankZero(comm_, rank_, [&] {
    const auto &names = model_.frictionJointNames();
    for (const StickSlipEvent &e : events) {
      const int joint = static_cast<int>(std::find(names.begin(), names.end(), e.joint) - names.begin());
      file_->appendScalar("/events/time", e.t);
      file_->appendScalarInt("/events/joint", joint);
      file_->appendScalarInt("/events/to_slip", e.toSlip ? 1 : 0);
      file_->appendScalarInt("/events/direction", e.direction);
      ++eventCount_;
    }
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsWriter::appendTypeEvents(const std::vector<TypeEvent> &events)
{
  PetscFunctionBeginUser;
  PetscCall(onRankZero(comm_, rank_, [&] {
    if (events.empty()) return; // most steps: no name lists to build
    const std::vector<std::string> names = eventComponents(model_), kinds = eventKinds(model_);
    for (const TypeEvent &e : events) {
      file_->appendScalar("/type_events/time", e.t);
      file_->appendScalarInt("/type_events/component",
                             static_cast<int>(std::find(names.begin(), names.end(), e.component) - names.begin()));
      file_->appendScalarInt("/type_events/kind",
                             static_cast<int>(std::find(kinds.begin(), kinds.end(), e.kind) - kinds.begin()));
      file_->appendScalarInt("/type_events/direction", e.direction);
      ++typeEventCount_;
    }
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsWriter::appendTracking(const TrackedModes &m, bool writeShape)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().output, 0, 0, 0, 0));
  PetscCall(onRankZero(comm_, rank_, [&] {
    file_->appendScalar("/tracking/time", m.t);
    file_->appendRow("/tracking/frequencies_hz", m.frequencyHz.data(), m.frequencyHz.size());
    file_->appendScalar("/tracking/tracked_hz", m.trackedHz);
    file_->appendScalar("/tracking/mac", m.mac);
    file_->appendScalarInt("/tracking/tracked_index", m.index);
    if (m.damped) { // a damped model (docs/output.md)
      file_->appendScalar("/tracking/tracked_damped_hz", m.trackedDampedHz);
      file_->appendScalar("/tracking/damping_ratio", m.trackedDampingRatio);
      file_->appendScalar("/tracking/damped_mac", m.dampedMac);
    }
    if (writeShape) {
      file_->appendScalar("/tracking/shape_time", m.t);
      file_->appendRow("/tracking/shapes", m.shape.data(), m.shape.size());
    }
    appendFollowed(m, writeShape);
  }));
  PetscCall(PetscLogEventEnd(logEvents().output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// Every followed mode (tracking.follow), one column each (docs/output.md).
void ResultsWriter::appendFollowed(const TrackedModes &m, bool writeShape)
{
  const std::size_t n = m.followed.size();
  std::vector<double> hz(n), mac(n), dampedHz(n), ratio(n), dampedMac(n), shapes;
  std::vector<int> index(n);
  for (std::size_t j = 0; j < n; ++j) {
    const FollowedMode &f = m.followed[j];
    hz[j] = f.hz, mac[j] = f.mac, index[j] = f.index;
    dampedHz[j] = f.dampedHz, ratio[j] = f.dampingRatio, dampedMac[j] = f.dampedMac;
    if (writeShape) shapes.insert(shapes.end(), f.shape.begin(), f.shape.end());
  }
  file_->appendRow("/tracking/followed_hz", hz.data(), n);
  file_->appendRow("/tracking/followed_mac", mac.data(), n);
  file_->appendRow("/tracking/followed_index", index.data(), n);
  if (m.damped) {
    file_->appendRow("/tracking/followed_damped_hz", dampedHz.data(), n);
    file_->appendRow("/tracking/followed_damping_ratio", ratio.data(), n);
    file_->appendRow("/tracking/followed_damped_mac", dampedMac.data(), n);
  }
  if (writeShape) file_->appendRow("/tracking/followed_shapes", shapes.data(), shapes.size());
  // Every reported mode's and the followed modes' energy shares, modes x kinds per row (docs/output.md).
  std::vector<double> shares;
  for (const EnergyShares &e : m.energyShares) shares.insert(shares.end(), e.begin(), e.end());
  file_->appendRow("/tracking/energy_shares", shares.data(), shares.size());
  shares.clear();
  for (const FollowedMode &f : m.followed) shares.insert(shares.end(), f.energyShares.begin(), f.energyShares.end());
  file_->appendRow("/tracking/followed_energy_shares", shares.data(), shares.size());
  if (!file_->exists("/tracking/energy_kinds")) file_->writeStrings("/tracking/energy_kinds", modeEnergyKindNames());
}

PetscErrorCode ResultsWriter::finish(const std::string &status, PetscInt steps, PetscInt rejected, double wallTime,
                                     double maxViolation)
{
  PetscFunctionBeginUser;
  PetscCall(onRankZero(comm_, rank_, [&] {
    if (!snapshotTimes_.empty()) writeXdmf();
    file_->setAttribute("/summary", "status", status);
    file_->setAttribute("/summary", "steps", static_cast<long long>(steps));
    file_->setAttribute("/summary", "rejected_steps", static_cast<long long>(rejected));
    file_->setAttribute("/summary", "wall_time_s", wallTime);
    file_->setAttribute("/summary", "max_constraint_violation", maxViolation);
    file_->setAttribute("/summary", "slack_rope_steps", static_cast<long long>(slackRopeSteps_));
    if (hasEnergyBalance_) {
      file_->setAttribute("/summary", "input_work_J", energyBalance_[0]);
      file_->setAttribute("/summary", "energy_excess_J", energyBalance_[1]);
      file_->setAttribute("/summary", "energy_involved_J", energyBalance_[2]);
    }
    if (!model_.frictionJointNames().empty())
      file_->setAttribute("/summary", "stick_slip_events", static_cast<long long>(eventCount_));
    if (!model_.eventSources().empty())
      file_->setAttribute("/summary", "type_events", static_cast<long long>(typeEventCount_));
    for (const auto &[name, value] : summaryNumbers_) file_->setAttribute("/summary", name, value);
    const bool taken = !file_->stillAtPath();
    file_->close();
    if (taken)
      throw std::runtime_error("the results file '" + path_ + "' was removed or replaced by another process during "
                               "the run: the results of this run are lost");
  }));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
