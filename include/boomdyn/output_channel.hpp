// A per-type output quantity: a value that follows linearly from one
// multiplier of the solution (value = factor * lambda[index]), e.g. the
// tension of a rope or a distance link. Types add channels when they
// are built (Model::outputChannels()); writers and monitors group them by
// `group` instead of asking for concrete constraint classes.
#pragma once

#include <petscsys.h>

#include <string>

namespace boomdyn {

struct OutputChannel {
  std::string group;    // e.g. "rope": all channels of a group form one table
  std::string name;     // component name
  std::string quantity; // e.g. "tension"
  std::string unit;     // e.g. "N"
  PetscInt index = 0;   // multiplier row, counted from 0
  double factor = 1;    // value = factor * lambda[index] (unscaled, SI units)
};

} // namespace boomdyn
