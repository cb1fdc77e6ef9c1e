#include "boomdyn/log_events.hpp"

namespace boomdyn {

namespace {
LogEvents events;
bool registered = false;
} // namespace

PetscErrorCode registerLogEvents()
{
  PetscFunctionBeginUser;
  if (!registered) {
    PetscClassId classid;
    PetscCall(PetscClassIdRegister("boomdyn", &classid));
    PetscCall(PetscLogEventRegister("BoomAssembly", classid, &events.assembly));
    PetscCall(PetscLogEventRegister("BoomStep", classid, &events.step));
    PetscCall(PetscLogEventRegister("BoomStart", classid, &events.start));
    PetscCall(PetscLogEventRegister("BoomMultipliers", classid, &events.multipliers));
    PetscCall(PetscLogEventRegister("BoomStatic", classid, &events.statics));
    PetscCall(PetscLogEventRegister("BoomEigen", classid, &events.eigen));
    PetscCall(PetscLogEventRegister("BoomOutput", classid, &events.output));
    registered = true;
  }
  PetscFunctionReturn(0);
}

const LogEvents &logEvents() { return events; }

} // namespace boomdyn
