#include "boomdyn/monitors.hpp"

namespace boomdyn {

PetscErrorCode EnergyCheck::start(const RunState &s, bool)
{
  PetscFunctionBeginUser;
  if (s.dynamic) (void)balance_.update(s.t, 0.0, s.energy);
  PetscFunctionReturn(0);
}

PetscErrorCode EnergyCheck::afterStep(const RunState &s, std::string *failure)
{
  PetscFunctionBeginUser;
  if (s.dynamic) *failure = balance_.update(s.t, s.h, s.energy);
  PetscFunctionReturn(0);
}

} // namespace boomdyn
