// The results file of a run (layout in docs/output.md), written by rank 0.
// Every method is collective-safe: on other ranks it does nothing except
// take part in the gathers of distributed vectors.
#pragma once

#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/frequency_tracker.hpp"
#include "boomdyn/hdf5_file.hpp"
#include "boomdyn/model.hpp"
#include "boomdyn/petsc_handle.hpp"
#include "boomdyn/rope_polylines.hpp"
#include "boomdyn/section_reading.hpp"
#include "boomdyn/sensors.hpp"
#include "boomdyn/spatial_body.hpp"
#include "boomdyn/stick_slip.hpp"

#include <petscvec.h>

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <utility>

namespace boomdyn {

struct RunInfo {
  std::string commandLine, petscOptions, version;
  int ranks = 1;
};

class ResultsWriter {
public:
  ResultsWriter(const Model &model, MPI_Comm comm) : model_(model), comm_(comm), ropes_(drawnRopes(model)) {}
  // Closes a file left open by an error that unwound the run, marking it
  // as failed (an HDF5 file, not a PETSc object; these live in handles).
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter &) = delete;
  ResultsWriter &operator=(const ResultsWriter &) = delete;

  // Creates the file (refuses to overwrite unless asked) and writes the
  // scene, run information and layout. layout: a vector with x's layout.
  PetscErrorCode open(const std::string &path, bool overwrite, const RunInfo &info, Vec layout);
  PetscErrorCode appendStep(double t, double dt, PetscInt iterations, double violation, const EnergyParts &energy,
                            const std::vector<SensorReading> &sensors);
  // Slack coordinates and unscaled multipliers of the same step (rank 0
  // data), and the values of the Model's output channels (/steps/outputs).
  PetscErrorCode appendJoints(const std::vector<double> &slacks, const std::vector<double> &multipliers,
                              const std::vector<double> &ropeTensions, const std::vector<double> &frameDeflections,
                              const std::vector<double> &outputs);
  // The sections of a spatial scene's frame sensors at the same step
  // (/frames/<name>; rank 0 data, SensorProbe::readSections).
  PetscErrorCode appendSections(const std::vector<SectionReading> &sections);
  // Full state snapshot; lambda holds unscaled multipliers in its last entries.
  PetscErrorCode appendState(double t, Vec q, Vec v, Vec lambda);
  PetscErrorCode writeModes(double t, const ModalResult &modes);
  // Friction readings of one step, and stick/slip events as they happen.
  PetscErrorCode appendFriction(const std::vector<FrictionReading> &readings);
  PetscErrorCode appendEvents(const std::vector<StickSlipEvent> &events);
  // Events of the registered types' event sources (/type_events, rank 0 data).
  PetscErrorCode appendTypeEvents(const std::vector<TypeEvent> &events);
  // One row of frequency tracking; with the tracked shape when writeShape.
  PetscErrorCode appendTracking(const TrackedModes &modes, bool writeShape);
  PetscErrorCode finish(const std::string &status, PetscInt steps, PetscInt rejected, double wallTime,
                        double maxViolation);
  const std::string &path() const { return path_; }
  // Steps at which a rope would have had to push (tension < 0), for /summary.
  void setSlackRopeSteps(PetscInt n) { slackRopeSteps_ = n; }
  // Further /summary attributes (name, value): the design numbers (design_numbers.hpp).
  void setSummaryNumbers(std::vector<std::pair<std::string, double>> numbers) { summaryNumbers_ = std::move(numbers); }
  // Energy balance of a dynamic run (/summary attributes input_work_J,
  // energy_excess_J, energy_involved_J).
  void setEnergyBalance(double inputWork, double excess, double involved)
  {
    energyBalance_[0] = inputWork, energyBalance_[1] = excess, energyBalance_[2] = involved, hasEnergyBalance_ = true;
  }

private:
  // The /tracking/followed_* columns of appendTracking (rank 0).
  void appendFollowed(const TrackedModes &modes, bool writeShape);
  PetscErrorCode gather(Vec v, std::vector<double> &out);
  // ParaView: booms sampled inside the elements at each state snapshot (rank 0),
  // and the XDMF file beside the results that describes them.
  void writeSampledBooms(double t, const std::vector<double> &q, const std::vector<double> &v);
  void writeSpatialBody(const SpatialBody &body, const std::vector<double> &q, const std::vector<double> &v);
  void writeXdmf() const;
  void appendStepRow(double t, double dt, PetscInt iterations, double violation, const EnergyParts &e,
                     const std::vector<SensorReading> &sensors);
  void writeModeArrays(double t, const ModalResult &modes);

  const Model &model_;
  MPI_Comm comm_;
  int rank_ = 0;
  std::string path_;
  std::unique_ptr<Hdf5File> file_;
  PetscHandle<VecScatter> toZero_;
  PetscHandle<Vec> gathered_;
  PetscInt slackRopeSteps_ = 0;
  double energyBalance_[3] = {0, 0, 0};
  bool hasEnergyBalance_ = false;
  std::vector<std::pair<std::string, double>> summaryNumbers_;
  std::vector<double> snapshotTimes_;
  std::size_t sampledPoints_ = 0, sampledSegments_ = 0, ropePoints_ = 0, ropeSegments_ = 0;
  std::vector<DrawnRope> ropes_; // drawn at every snapshot (rope_polylines.hpp)
  long long eventCount_ = 0, typeEventCount_ = 0;
  // /sensors/<name>/position and /velocity of every sensor, spelled once
  // (not two new strings per sensor and step).
  std::vector<std::string> sensorPaths_;
  std::vector<std::string> sectionPaths_; // /frames/<name>/triad, twist, angular_velocity, strains per frame
  // XDMF grids of the first xdmfGrids_ snapshots (booms, ropes), for the
  // sampled sizes in xdmfShape_ (writeXdmf adds the new snapshots' only).
  mutable std::string xdmfBooms_, xdmfRopes_;
  mutable std::size_t xdmfGrids_ = 0;
  mutable std::array<std::size_t, 4> xdmfShape_ = {0, 0, 0, 0};
  // writeSampledBooms' arrays, kept between snapshots (no allocations per snapshot).
  std::vector<double> samplePoints_, sampleVelocity_, sampleStrain_, sampleCurvature_, sampleRopePoints_;
  std::vector<double> sampleTwist_, sampleTorsion_, sampleD2_, sampleD3_; // spatial scenes
  std::vector<int> sampleSegments_, sampleRopeSegments_;
  std::chrono::steady_clock::time_point lastFlush_ = std::chrono::steady_clock::now(), lastXdmf_ = lastFlush_;
};

} // namespace boomdyn
