// Follows the slack coordinates of the sliding joints: after a converged
// Newton solve it brings every joint's s to every rank, moves joints whose
// contact point has left its track element to the element that holds it
// (and then rebuilds the assembly pattern), and reports a slider that has
// left its track altogether.
#pragma once

#include "boomdyn/assembler.hpp"

#include <string>
#include <vector>

namespace boomdyn {

class Model;

// For messages when a run fails: the sliding joints whose contact coordinate
// (slacks, in the order of model.slidingJoints()) lies within margin times
// the track length of an end of its track, e.g. "sliding joint 'j2' at
// s = 1.99996 m, 4e-05 m from the end of its track 'boom1' (2 m)"; "" if none.
std::string contactsNearTrackEnds(const Model &model, const std::vector<double> &slacks, double margin = 0.01);

class SliderTracker {
public:
  explicit SliderTracker(Assembler &assembler) : assembler_(assembler) {}
  ~SliderTracker();
  SliderTracker(const SliderTracker &) = delete;
  SliderTracker &operator=(const SliderTracker &) = delete;

  PetscErrorCode setUp(Vec layout);
  // relocated: some joint changed element (pattern rebuilt: redo the solve);
  // offTrack: non-empty message if a slider left its track.
  PetscErrorCode update(Vec x, double t, bool *relocated, std::string *offTrack);
  // Material coordinates that define each joint's current track element
  // (for checkpoints), and the inverse: put the joints back on those elements
  // (collective: rebuilds the pattern).
  std::vector<double> locations() const;
  PetscErrorCode setLocations(const std::vector<double> &s);
  bool active() const { return !assembler_.model().slidingJoints().empty(); }

private:
  Assembler &assembler_;
  VecScatter scatter_ = nullptr;
  Vec slacks_ = nullptr;
};

} // namespace boomdyn
