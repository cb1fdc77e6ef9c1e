// A per-type output quantity, one column of /steps/outputs. Two kinds:
//  - multiplier channels: value = factor * lambda[index], e.g. the tension
//    of an inextensible rope or a distance link;
//  - state channels (`value` or `timedValue` set): value = value(q, v) (or
//    timedValue(t, q, v)) of the coordinates listed in `watched` (their
//    positions and velocities, in that order), e.g. the tension, length and
//    stretch of an elastic rope.
// Types add channels when they are built (Model::outputChannels()); writers
// and monitors group them by `group` instead of asking for concrete classes,
// and SensorProbe::readOutputs gathers and evaluates both kinds, so a new
// per-type quantity needs no writer code.
#pragma once

#include <petscsys.h>

#include <functional>
#include <string>
#include <vector>

namespace boomdyn {

struct OutputChannel {
  std::string group;    // e.g. "rope": all channels of a group form one table
  std::string name;     // component name
  std::string quantity; // e.g. "tension"
  std::string unit;     // e.g. "N"
  PetscInt index = 0;   // multiplier channels: multiplier row, counted from 0
  double factor = 1;    // multiplier channels: value = factor * lambda[index] (unscaled, SI units)
  // State channels: global coordinates whose values (q) and velocities (v)
  // are handed to `value`, in this order. Evaluated on rank 0 only.
  std::vector<PetscInt> watched;
  std::function<double(const double *q, const double *v)> value;
  // Or value(t, q, v) for quantities that also depend on time (a winch's
  // rope: its unstretched length follows the winch).
  std::function<double(double t, const double *q, const double *v)> timedValue;

  bool fromState() const { return static_cast<bool>(value) || static_cast<bool>(timedValue); }
  double evaluate(double t, const double *q, const double *v) const { return value ? value(q, v) : timedValue(t, q, v); }

  static OutputChannel ofMultiplier(std::string group, std::string name, std::string quantity, std::string unit,
                                    PetscInt index, double factor)
  {
    OutputChannel c;
    c.group = std::move(group), c.name = std::move(name), c.quantity = std::move(quantity), c.unit = std::move(unit);
    c.index = index, c.factor = factor;
    return c;
  }
  static OutputChannel ofState(std::string group, std::string name, std::string quantity, std::string unit,
                               std::vector<PetscInt> watched, std::function<double(const double *, const double *)> value)
  {
    OutputChannel c;
    c.group = std::move(group), c.name = std::move(name), c.quantity = std::move(quantity), c.unit = std::move(unit);
    c.watched = std::move(watched), c.value = std::move(value);
    return c;
  }
  static OutputChannel ofTimedState(std::string group, std::string name, std::string quantity, std::string unit,
                                    std::vector<PetscInt> watched,
                                    std::function<double(double, const double *, const double *)> value)
  {
    OutputChannel c;
    c.group = std::move(group), c.name = std::move(name), c.quantity = std::move(quantity), c.unit = std::move(unit);
    c.watched = std::move(watched), c.timedValue = std::move(value);
    return c;
  }
};

} // namespace boomdyn
