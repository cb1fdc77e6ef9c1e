// Sensors: position and velocity of named material points, gathered on
// rank 0 from the distributed state through one small VecScatter; in
// spatial scenes also the sections of frame sensors (section_reading.hpp).
#pragma once

#include "boomdyn/model.hpp"
#include "boomdyn/petsc_handle.hpp"
#include "boomdyn/section_reading.hpp"

#include <petscvec.h>

#include <vector>

namespace boomdyn {

// position, velocity: x and y (in a spatial scene the first two of the
// three components, which position3 and velocity3 hold whole).
struct SensorReading {
  Vec2 position = Vec2::Zero(), velocity = Vec2::Zero();
  Vec3 position3 = Vec3::Zero(), velocity3 = Vec3::Zero();
};

class SensorProbe {
public:
  explicit SensorProbe(const Model &model) : model_(model) {}

  // layout: any vector with the layout of x.
  PetscErrorCode setUp(Vec layout);
  // Readings of every sensor (valid on rank 0 only; other ranks get zeros).
  PetscErrorCode read(Vec q, Vec v, std::vector<SensorReading> &out);
  // Slack coordinates of the sliding joints (from q) and all unscaled
  // multipliers (from lambda, layout of x), on rank 0.
  PetscErrorCode readJoints(Vec q, Vec lambda, std::vector<double> &slacks, std::vector<double> &multipliers);
  // Per frictional joint: s, ds/dt, z, dz/dt, normal force (rank 0): lambda_n,
  // or at a padded joint the pad force f.
  PetscErrorCode readFriction(Vec q, Vec v, Vec lambda, std::vector<double> &values);
  // Moving-frame deflections of the scene's frame sensors (rank 0; planar scenes).
  PetscErrorCode readFrames(Vec q, std::vector<double> &deflections);
  // The sections of a spatial scene's frame sensors (rank 0; empty in planar scenes).
  PetscErrorCode readSections(Vec q, Vec v, std::vector<SectionReading> &out);
  // Every output channel's value (Model::outputChannels(), in order) at this
  // state (rank 0; empty elsewhere): multiplier channels from `multipliers`
  // (all unscaled multipliers, as readJoints gives them), state channels
  // from the values and velocities of their watched coordinates.
  PetscErrorCode readOutputs(double t, Vec q, Vec v, const std::vector<double> &multipliers,
                             std::vector<double> &outputs);
  // Values and velocities of the event sources' watched coordinates, one
  // source after the other in Model::eventSources() order (rank 0).
  PetscErrorCode readEventCoordinates(Vec q, Vec v, std::vector<double> &qs, std::vector<double> &vs);

private:
  // scatterValues(sc, src, dst, out), or on one rank the same values read
  // straight from src at the scatter's indices (a PETSc scatter per read was
  // a visible part of the per-step output).
  PetscErrorCode pick(VecScatter sc, Vec src, Vec dst, std::vector<double> &out) const;
  // scatterToRankZero, remembering the indices for pick() on one rank.
  PetscErrorCode makeScatter(Vec layout, const std::vector<PetscInt> &idx, PetscHandle<VecScatter> &sc,
                             PetscHandle<Vec> &values);

  const Model &model_;
  bool serial_ = false;                                                 // one rank: pick() reads directly
  std::vector<std::pair<VecScatter, std::vector<PetscInt>>> indices_;   // per scatter (one rank only)
  std::vector<double> qs_, vs_;                                         // readOutputs' work arrays
  std::vector<CenterlineLocation> locations_;       // planar point sensors
  std::vector<SpatialLocation> spatialLocations_;   // spatial point sensors
  std::vector<SpatialLocation> sectionLocations_;   // spatial frame sensors
  PetscHandle<VecScatter> sectionScatter_;
  PetscHandle<Vec> sectionValues_;
  PetscHandle<VecScatter> scatter_, slackScatter_, lambdaScatter_, frameScatter_, frictionScatter_, normalScatter_,
      channelScatter_, eventScatter_, padScatter_;
  PetscHandle<Vec> gathered_, slacks_, multipliers_, frameValues_, frictionValues_, normalValues_, channelValues_,
      eventValues_, padValues_;
  struct PadFriction {
    std::size_t friction; // index in Model::frictions()
    PetscInt offset;      // of the track's coordinates in padValues_; the slider's, then s follow
  };
  std::vector<PadFriction> padFrictions_;
  // Per state output channel, where its watched coordinates start in
  // channelValues_: channels with the same watched list (a pad's three
  // channels watch both bodies whole) share one copy of it.
  std::vector<std::size_t> channelOffsets_;
  struct Frame {
    const Body *body;
    double s;        // material point measured
    PetscInt offset; // of the body's coordinates in frameValues_; its slack value follows them
  };
  std::vector<Frame> frames_;
  int rank_ = 0;
};

} // namespace boomdyn
