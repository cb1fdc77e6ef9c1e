#include "boomdyn/sensors.hpp"

#include "boomdyn/pad_contact.hpp"

#include "boomdyn/gather.hpp"

#include "boomdyn/lugre_friction.hpp"

#include <algorithm>

namespace boomdyn {

// A scatter of the given global indices of `layout` to a sequential vector on rank 0.
static PetscErrorCode scatterToRankZero(Vec layout, int rank, const std::vector<PetscInt> &idx, VecScatter *sc, Vec *out)
{
  IS is;
  PetscFunctionBeginUser;
  const PetscInt n = rank == 0 ? static_cast<PetscInt>(idx.size()) : 0;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, idx.data(), PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, out));
  PetscCall(VecScatterCreate(layout, is, *out, nullptr, sc));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::makeScatter(Vec layout, const std::vector<PetscInt> &idx, PetscHandle<VecScatter> &sc,
                                        PetscHandle<Vec> &values)
{
  PetscFunctionBeginUser;
  PetscCall(scatterToRankZero(layout, rank_, idx, sc.address(), values.address()));
  // (An index list with a negative entry, which a scatter skips, keeps the scatter.)
  if (serial_ && std::all_of(idx.begin(), idx.end(), [](PetscInt i) { return i >= 0; }))
    indices_.emplace_back(sc.get(), idx);
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::pick(VecScatter sc, Vec src, Vec dst, std::vector<double> &out) const
{
  PetscFunctionBeginUser;
  const std::vector<PetscInt> *idx = nullptr;
  for (const auto &entry : indices_)
    if (entry.first == sc) idx = &entry.second;
  if (!idx) {
    PetscCall(scatterValues(sc, src, dst, out));
    PetscFunctionReturn(0);
  }
  // One rank: the local array is the whole vector, a global index a local one.
  const PetscScalar *a;
  PetscCall(VecGetArrayRead(src, &a));
  out.resize(idx->size());
  for (std::size_t k = 0; k < idx->size(); ++k) out[k] = a[(*idx)[k]];
  PetscCall(VecRestoreArrayRead(src, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::readFrames(Vec q, std::vector<double> &deflections)
{
  std::vector<double> vals;
  PetscFunctionBeginUser;
  PetscCall(pick(frameScatter_, q, frameValues_, vals));
  deflections.clear();
  if (rank_ != 0) PetscFunctionReturn(0);
  for (const Frame &f : frames_) {
    const double *body = vals.data() + f.offset;
    const double sAxis = std::clamp(body[f.body->numCoordinates()], 0.0, f.body->length());
    // Position of material point s from the body's gathered coordinates.
    auto position = [&](double s) {
      const CenterlineLocation loc = f.body->locate(s);
      double local[8];
      for (int k = 0; k < loc.count; ++k) local[k] = body[loc.dofs[k] - f.body->firstCoordinate()];
      CenterlineSample p;
      f.body->sample(loc, s, local, p);
      return Vec2(p.r[0]);
    };
    const Vec2 origin = position(0.0), axis = (position(sAxis) - origin).normalized();
    deflections.push_back((position(f.s) - origin).dot(Vec2(-axis.y(), axis.x())));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::readSections(Vec q, Vec v, std::vector<SectionReading> &out)
{
  std::vector<double> qs, vs;
  PetscFunctionBeginUser;
  out.clear();
  if (sectionLocations_.empty()) PetscFunctionReturn(0);
  PetscCall(pick(sectionScatter_, q, sectionValues_, qs));
  PetscCall(pick(sectionScatter_, v, sectionValues_, vs));
  if (rank_ != 0) PetscFunctionReturn(0);
  std::size_t offset = 0, k = 0;
  for (const FrameSensor &f : model_.frameSensors()) {
    if (!f.spatialBody) continue;
    const SpatialLocation &loc = sectionLocations_[k++];
    out.push_back(readSection(*f.spatialBody, loc, f.s, qs.data() + offset, vs.data() + offset));
    offset += loc.count;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::readFriction(Vec q, Vec v, Vec lambda, std::vector<double> &values)
{
  std::vector<double> qs, vs, ln;
  PetscFunctionBeginUser;
  PetscCall(pick(frictionScatter_, q, frictionValues_, qs));
  PetscCall(pick(frictionScatter_, v, frictionValues_, vs));
  PetscCall(pick(normalScatter_, lambda, normalValues_, ln));
  values.clear();
  if (!padFrictions_.empty()) { // the normal force of a padded joint is the pad's f(q, v)
    std::vector<double> pq, pv;
    PetscCall(pick(padScatter_, q, padValues_, pq));
    PetscCall(pick(padScatter_, v, padValues_, pv));
    if (rank_ == 0)
      for (const PadFriction &p : padFrictions_) {
        const LuGreFriction &f = *model_.frictions()[p.friction];
        const SlidingJoint &joint = f.joint();
        std::vector<PetscInt> dofs;
        joint.coordinates(dofs);
        const Body &track = joint.track(), &slider = joint.slider();
        const CenterlineLocation &tl = joint.trackLocation(), &sl = joint.sliderLocation();
        std::vector<double> lq(dofs.size()), lv(dofs.size());
        auto copy = [&](PetscInt at, std::size_t i) { lq[i] = pq[at], lv[i] = pv[at]; };
        for (int i = 0; i < tl.count; ++i) copy(p.offset + tl.dofs[i] - track.firstCoordinate(), i);
        const PetscInt sliderOffset = p.offset + track.numCoordinates();
        for (int i = 0; i < sl.count; ++i) copy(sliderOffset + sl.dofs[i] - slider.firstCoordinate(), tl.count + i);
        copy(sliderOffset + slider.numCoordinates(), dofs.size() - 1);
        ln[p.friction] = f.pad()->state(lq.data(), lv.data()).force;
      }
  }
  for (std::size_t k = 0; k < ln.size(); ++k) {
    const double row[5] = {qs[2 * k], vs[2 * k], qs[2 * k + 1], vs[2 * k + 1], ln[k]};
    values.insert(values.end(), row, row + 5);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::readJoints(Vec q, Vec lambda, std::vector<double> &slacks, std::vector<double> &multipliers)
{
  PetscFunctionBeginUser;
  PetscCall(pick(slackScatter_, q, slacks_, slacks));
  PetscCall(pick(lambdaScatter_, lambda, multipliers_, multipliers));
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::setUp(Vec layout)
{
  MPI_Comm comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)layout, &comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank_));
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  serial_ = size == 1;
  indices_.clear();
  std::vector<PetscInt> idx;
  for (const Sensor &s : model_.sensors()) {
    if (s.spatialBody) {
      spatialLocations_.push_back(s.spatialBody->locate(s.s));
      const SpatialLocation &loc = spatialLocations_.back();
      idx.insert(idx.end(), loc.dofs.begin(), loc.dofs.begin() + loc.count);
      continue;
    }
    locations_.push_back(s.body->locate(s.s));
    const CenterlineLocation &loc = locations_.back();
    idx.insert(idx.end(), loc.dofs.begin(), loc.dofs.begin() + loc.count);
  }
  // Rank 0 receives every sensor's coordinates; the other ranks ask for none.
  PetscCall(makeScatter(layout, idx, scatter_, gathered_));
  std::vector<PetscInt> slack, rows;
  for (const auto &j : model_.slidingJoints()) slack.push_back(j->slackIndex());
  for (PetscInt r = 0; r < model_.numMultipliers(); ++r) rows.push_back(model_.numCoordinates() + r);
  PetscCall(makeScatter(layout, slack, slackScatter_, slacks_));
  PetscCall(makeScatter(layout, rows, lambdaScatter_, multipliers_));
  // Frame sensors: the whole body (the axis point moves along it) and the joint's slack coordinate.
  std::vector<PetscInt> frameIdx, sectionIdx;
  for (const FrameSensor &f : model_.frameSensors()) {
    if (f.spatialBody) { // a spatial scene's: the section at s
      sectionLocations_.push_back(f.spatialBody->locate(f.s));
      const SpatialLocation &loc = sectionLocations_.back();
      sectionIdx.insert(sectionIdx.end(), loc.dofs.begin(), loc.dofs.begin() + loc.count);
      continue;
    }
    const Body *body = f.body;
    PetscInt slack = -1;
    for (const auto &j : model_.slidingJoints())
      if (j->name() == f.axisJoint) slack = j->slackIndex();
    frames_.push_back({body, f.s, static_cast<PetscInt>(frameIdx.size())});
    for (PetscInt k = 0; k < body->numCoordinates(); ++k) frameIdx.push_back(body->firstCoordinate() + k);
    frameIdx.push_back(slack);
  }
  PetscCall(makeScatter(layout, frameIdx, frameScatter_, frameValues_));
  PetscCall(makeScatter(layout, sectionIdx, sectionScatter_, sectionValues_));
  std::vector<PetscInt> frictionIdx, normalIdx;
  std::vector<PetscInt> padIdx; // padded joints: track and slider whole, then s (the contact moves)
  for (std::size_t k = 0; k < model_.frictions().size(); ++k) {
    const LuGreFriction *f = model_.frictions()[k];
    frictionIdx.push_back(f->joint().slackIndex());
    frictionIdx.push_back(f->stateIndex());
    if (f->pad()) { // a placeholder row (readFriction replaces the value by the pad force)
      normalIdx.push_back(model_.numCoordinates());
      padFrictions_.push_back({k, static_cast<PetscInt>(padIdx.size())});
      for (const Body *body : {&f->joint().track(), &f->joint().slider()})
        for (PetscInt k = 0; k < body->numCoordinates(); ++k) padIdx.push_back(body->firstCoordinate() + k);
      padIdx.push_back(f->joint().slackIndex());
    } else
      normalIdx.push_back(f->normalRow());
  }
  PetscCall(makeScatter(layout, padIdx, padScatter_, padValues_));
  PetscCall(makeScatter(layout, frictionIdx, frictionScatter_, frictionValues_));
  PetscCall(makeScatter(layout, normalIdx, normalScatter_, normalValues_));
  // State output channels and event sources: their watched coordinates, one after the other.
  std::vector<PetscInt> channelIdx, eventIdx;
  std::vector<std::pair<const std::vector<PetscInt> *, std::size_t>> lists; // distinct watched lists, offsets
  channelOffsets_.clear();
  for (const OutputChannel &ch : model_.outputChannels()) {
    if (!ch.fromState()) continue;
    auto same = std::find_if(lists.begin(), lists.end(), [&](const auto &l) { return *l.first == ch.watched; });
    if (same != lists.end()) {
      channelOffsets_.push_back(same->second);
      continue;
    }
    lists.push_back({&ch.watched, channelIdx.size()});
    channelOffsets_.push_back(channelIdx.size());
    channelIdx.insert(channelIdx.end(), ch.watched.begin(), ch.watched.end());
  }
  for (const EventSource &e : model_.eventSources()) eventIdx.insert(eventIdx.end(), e.watched.begin(), e.watched.end());
  PetscCall(makeScatter(layout, channelIdx, channelScatter_, channelValues_));
  PetscCall(makeScatter(layout, eventIdx, eventScatter_, eventValues_));
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::readOutputs(double t, Vec q, Vec v, const std::vector<double> &multipliers,
                                        std::vector<double> &outputs)
{
  std::vector<double> &qs = qs_, &vs = vs_;
  PetscFunctionBeginUser;
  PetscCall(pick(channelScatter_, q, channelValues_, qs));
  PetscCall(pick(channelScatter_, v, channelValues_, vs));
  outputs.clear();
  if (rank_ != 0) PetscFunctionReturn(0);
  std::size_t k = 0; // state channel
  for (const OutputChannel &ch : model_.outputChannels()) {
    if (!ch.fromState()) {
      outputs.push_back(ch.factor * multipliers.at(static_cast<std::size_t>(ch.index)));
      continue;
    }
    const std::size_t offset = channelOffsets_[k++];
    outputs.push_back(ch.evaluate(t, qs.data() + offset, vs.data() + offset));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::readEventCoordinates(Vec q, Vec v, std::vector<double> &qs, std::vector<double> &vs)
{
  PetscFunctionBeginUser;
  PetscCall(pick(eventScatter_, q, eventValues_, qs));
  PetscCall(pick(eventScatter_, v, eventValues_, vs));
  PetscFunctionReturn(0);
}

PetscErrorCode SensorProbe::read(Vec q, Vec v, std::vector<SensorReading> &out)
{
  PetscFunctionBeginUser;
  out.assign(model_.sensors().size(), SensorReading{});
  std::vector<double> qv[2];
  PetscCall(pick(scatter_, q, gathered_, qv[0]));
  PetscCall(pick(scatter_, v, gathered_, qv[1]));
  if (rank_ != 0) PetscFunctionReturn(0);
  if (!spatialLocations_.empty()) { // a spatial scene: every sensor is on a spatial body
    std::size_t offset = 0;
    for (std::size_t i = 0; i < spatialLocations_.size(); ++i) {
      const SpatialLocation &loc = spatialLocations_[i];
      const Sensor &s = model_.sensors()[i];
      SpatialSample p;
      s.spatialBody->sample(loc, s.s, qv[0].data() + offset, p);
      out[i].position3 = p.r;
      out[i].velocity3 = p.r_q.leftCols(loc.count) * Eigen::Map<const Eigen::VectorXd>(qv[1].data() + offset, loc.count);
      out[i].position = out[i].position3.head<2>(), out[i].velocity = out[i].velocity3.head<2>();
      offset += loc.count;
    }
    PetscFunctionReturn(0);
  }
  std::size_t offset = 0;
  for (std::size_t i = 0; i < locations_.size(); ++i) {
    const CenterlineLocation &loc = locations_[i];
    const Sensor &s = model_.sensors()[i];
    CenterlineSample p;
    s.body->sample(loc, s.s, qv[0].data() + offset, p);
    out[i].position = p.r[0];
    // Velocity: d r/dq v (exact for linear centerlines; first order term otherwise is the same).
    out[i].velocity = p.r_q[0].leftCols(loc.count) * Eigen::Map<const Eigen::VectorXd>(qv[1].data() + offset, loc.count);
    offset += loc.count;
  }
  PetscFunctionReturn(0);
}

} // namespace boomdyn
