// boomdyn: flexible multibody dynamics of planar telescopic crane booms.
//
//   boomdyn SCENE.yaml [-o OUT.h5] [-boom_overwrite] [-boom_quiet] [PETSc options]
//
// Reads a scene (docs/scenes.md), runs its static, dynamic or modal
// analysis and writes an HDF5 results file (docs/output.md).
#include "options.hpp"
#include "run.hpp"
#include "signals.hpp"

#include "boomdyn/model.hpp"
#include "boomdyn/scene_reader.hpp"

#include <slepcsys.h>

#include <cstdio>
#include <exception>

static const char help[] = "boomdyn SCENE.yaml [-o OUT.h5] [-boom_overwrite] [-boom_quiet] [-boom_elements N]\n"
                           "  [-boom_elements_<body> N] [-ts_dt h] [-ts_max_time T] [-boom_rho_inf r]\n"
                           "  [-boom_state_interval dt] [-boom_modal_count k] [-boom_load_steps n]\n"
                           "  [-boom_tracking_interval dt] [-boom_checkpoint_interval dt] [-boom_checkpoint FILE]\n"
                           "  [-boom_restart FILE] [PETSc options]\n";

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  int code = 0;
  try {
    boomdyn::AppOptions opts;
    PetscCall(boomdyn::readAppOptions(argc, argv, &opts));
    boomdyn::Scene scene = boomdyn::readSceneFile(opts.scenePath);
    PetscCall(boomdyn::applySceneOverrides(&scene));
    boomdyn::installInterruptHandlers();
    PetscCall(boomdyn::runScene(scene, opts, argc, argv));
  } catch (const boomdyn::Interrupted &e) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "boomdyn: %s\n", e.what()));
    code = 128 + boomdyn::interruptSignal();
  } catch (const std::exception &e) {
    // Bad scenes and mechanisms: a clear message, a non-zero exit, no core dump.
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "boomdyn: error: %s\n", e.what()));
    code = 1;
  }
  PetscBool slepc;
  PetscCall(SlepcInitialized(&slepc));
  if (slepc) PetscCall(SlepcFinalize());
  PetscCall(PetscFinalize());
  return code;
}
