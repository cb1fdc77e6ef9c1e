// One run of a scene: static, dynamic or modal analysis, with results written
// as described in docs/output.md.
#pragma once

#include "options.hpp"

#include "boomdyn/scene.hpp"

#include <petscsys.h>

namespace boomdyn {

PetscErrorCode runScene(const Scene &scene, const AppOptions &opts, int argc, char **argv);

} // namespace boomdyn
