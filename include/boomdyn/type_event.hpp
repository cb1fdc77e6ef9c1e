// A generic event log for the registered types: a type registers an
// EventSource (Model::eventSources()) that looks at the positions and
// velocities of the coordinates it watches after every converged step and
// returns the discrete changes it sees (a rope going slack or taut, a pad
// lifting off). TypeEventsOutput (src/simulation/type_events_output.cpp)
// writes them to /type_events and prints one console line per event; the
// stick/slip events of friction keep their own log (/events).
#pragma once

#include <petscsys.h>

#include <functional>
#include <string>
#include <vector>

namespace boomdyn {

struct TypeEvent {
  double t = 0;          // time of the change (a source may interpolate inside the step)
  std::string component; // the component's name
  std::string kind;      // one of its source's `kinds`
  int direction = 0;     // a source-defined sign (docs of the type say what it means)
};

struct EventSource {
  std::string component;          // name of the component that owns the source
  std::vector<std::string> kinds; // every kind it may report (HDF5 stores indices into the union)
  std::vector<PetscInt> watched;  // global coordinates handed to detect, in this order
  // Called on rank 0: with first = true at the start of a run (and of a
  // restarted run) to take the initial state without reporting, then after
  // every converged dynamic step at time t with the step h that reached it.
  // q and v hold the watched coordinates' values and velocities.
  std::function<void(double t, double h, const double *q, const double *v, bool first, std::vector<TypeEvent> &events)>
      detect;
};

} // namespace boomdyn
