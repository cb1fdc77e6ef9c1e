// Runs the post-step hooks that types registered (Model::postStepHooks(),
// post_step_hook.hpp): after a converged Newton solve it brings every
// watched value to every rank and hands it to the hooks. Today the sliding
// joints register one each: a joint whose contact point has left its track
// element moves to the element that holds it (the tracker then rebuilds the
// assembly pattern), and a slider that has left its track stops the run.
#pragma once

#include "boomdyn/assembler.hpp"
#include "boomdyn/petsc_handle.hpp"

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
  SliderTracker(const SliderTracker &) = delete;
  SliderTracker &operator=(const SliderTracker &) = delete;

  PetscErrorCode setUp(Vec layout);
  // relocated: some hook changed the topology (pattern rebuilt: redo the
  // solve); offTrack: non-empty message if a hook stops the run (a slider
  // left its track).
  // Hooks that change the chart only (PostStepHook::changesChartOnly) are
  // left out here and run by rechart() at an accepted state.
  PetscErrorCode update(Vec x, double t, bool *relocated, std::string *offTrack);
  // Runs the chart-changing hooks at an accepted step or converged load
  // step x (collective).
  PetscErrorCode rechart(Vec x, double t);
  // Each hook's checkpointed location (for sliding joints: the material
  // coordinate that defines the current track element), and the inverse
  // (collective: rebuilds the pattern). Hooks without a location are skipped.
  std::vector<double> locations() const;
  PetscErrorCode setLocations(const std::vector<double> &s);
  // The hooks' other checkpointed state (PostStepHook::state, e.g. beam node
  // references), concatenated in hook order, and the inverse.
  std::vector<double> states() const;
  PetscErrorCode setStates(const std::vector<double> &values);
  bool active() const { return !assembler_.model().postStepHooks().empty(); }

private:
  Assembler &assembler_;
  PetscHandle<VecScatter> scatter_;
  PetscHandle<Vec> slacks_; // the watched values of all hooks, in hook order
};

} // namespace boomdyn
