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

#include <chrono>
#include <cstdio>
#include <thread>
#include <exception>
#include <new>
#include <string>

static const char help[] = "boomdyn SCENE.yaml [-o OUT.h5] [-boom_overwrite] [-boom_quiet] [-boom_elements N]\n"
                           "  [-boom_elements_<body> N] [-ts_dt h] [-ts_max_time T] [-boom_rho_inf r]\n"
                           "  [-boom_state_interval dt] [-boom_modal_count k] [-boom_load_steps n]\n"
                           "  [-boom_tracking_interval dt] [-boom_checkpoint_interval dt] [-boom_checkpoint FILE]\n"
                           "  [-boom_restart FILE] [PETSc options]\n";

namespace {

// PETSc errors (a failed factorization, a bad option value, ...) are reported
// as one line naming the scene, like every other error, instead of PETSc's
// traceback and an MPI_Abort: the handler keeps the first message and lets
// the error code travel up to main.
std::string firstPetscError;

PetscErrorCode keepFirstError(MPI_Comm, int line, const char *function, const char *file, PetscErrorCode n,
                              PetscErrorType type, const char *message, void *)
{
  if (type == PETSC_ERROR_INITIAL && firstPetscError.empty()) {
    const char *text = nullptr;
    PetscErrorMessage(n, &text, nullptr);
    firstPetscError = std::string(message && *message ? message : (text ? text : "PETSc error")) + " (in " +
                      (function ? function : "?") + ", " + (file ? file : "?") + ":" + std::to_string(line) + ")";
  }
  return n;
}

// Messages that do not say which scene they are about get its name.
std::string aboutScene(const std::string &message, const std::string &scene)
{
  return scene.empty() || message.find(scene) != std::string::npos ? message : scene + ": " + message;
}

// Every rank ends here, with its error line (empty: success). An error that
// only some ranks met leaves the others waiting in a collective call
// forever: a failing rank that does not see the others arrive within
// -boom_error_wait seconds prints its own message and aborts the job. When
// all arrive, rank 0 prints its message, or the first failing rank prints
// its own if rank 0 has none, and all exit with the largest code.
PetscErrorCode reportTogether(const std::string &line, int *code)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (size == 1) {
    if (!line.empty()) PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s\n", line.c_str()));
    PetscFunctionReturn(0);
  }
  PetscReal wait = 30.0;
  PetscCall(PetscOptionsGetReal(nullptr, "boom_", "-error_wait", &wait, nullptr));
  MPI_Request request;
  int arrived = 0;
  PetscCallMPI(MPI_Ibarrier(PETSC_COMM_WORLD, &request));
  const auto start = std::chrono::steady_clock::now();
  while (true) {
    PetscCallMPI(MPI_Test(&request, &arrived, MPI_STATUS_IGNORE));
    if (arrived) break;
    if (!line.empty() && std::chrono::steady_clock::now() - start > std::chrono::duration<double>(wait)) {
      std::fprintf(stderr, "%s\nboomdyn: rank %d failed alone and the other ranks cannot finish without it; aborting\n",
                   line.c_str(), rank);
      std::fflush(stderr);
      MPI_Abort(PETSC_COMM_WORLD, *code ? *code : 1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  int failed = line.empty() ? size : rank, firstFailed, worst;
  PetscCallMPI(MPI_Allreduce(&failed, &firstFailed, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(code, &worst, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD));
  *code = worst;
  if (rank == firstFailed) {
    std::fprintf(rank == 0 ? stdout : stderr, "%s\n", line.c_str());
    std::fflush(rank == 0 ? stdout : stderr);
  }
  PetscFunctionReturn(0);
}

} // namespace

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  PetscCall(PetscPushErrorHandler(keepFirstError, nullptr));
  int code = 0;
  std::string scenePath, errorLine;
  try {
    boomdyn::AppOptions opts;
    PetscErrorCode ierr = boomdyn::readAppOptions(argc, argv, &opts);
    scenePath = opts.scenePath;
    if (!ierr) {
      boomdyn::Scene scene = boomdyn::readSceneFile(opts.scenePath);
      ierr = boomdyn::applySceneOverrides(&scene);
      PetscInt parts = 0;
      PetscBool report = PETSC_FALSE;
      if (!ierr) ierr = PetscOptionsGetInt(nullptr, "boom_", "-partition_report", &parts, &report);
      if (!ierr && report) {
        ierr = boomdyn::reportPartitions(scene, parts);
      } else if (!ierr) {
        boomdyn::installInterruptHandlers();
        ierr = boomdyn::runScene(scene, opts, argc, argv);
      }
    }
    if (ierr) {
      // A failed LU factorization of the saddle-point system means it is singular.
      std::string message = firstPetscError;
      if (message.find("actorization") != std::string::npos || message.find("MUMPS") != std::string::npos ||
          message.find("pivot") != std::string::npos)
        message = "the system matrix is singular: a body or motion without support, or redundant or contradictory "
                  "constraints (two drives on one joint, a clamp plus an angle drive at one point, ...); solver said: " +
                  message;
      errorLine = "boomdyn: error: " + aboutScene(message, scenePath);
      code = 1;
    }
  } catch (const boomdyn::Interrupted &e) {
    errorLine = std::string("boomdyn: ") + e.what();
    code = 128 + boomdyn::interruptSignal();
  } catch (const std::bad_alloc &) {
    errorLine = "boomdyn: error: " + aboutScene("out of memory: the scene needs more memory than this machine has "
                                                "(a mesh too large? see -boom_elements)", scenePath);
    code = 1;
  } catch (const std::exception &e) {
    // Bad scenes and mechanisms: a clear message, a non-zero exit, no core dump.
    errorLine = "boomdyn: error: " + aboutScene(e.what(), scenePath);
    code = 1;
  }
  PetscCall(reportTogether(errorLine, &code));
  PetscCall(PetscPopErrorHandler()); // pushed above; unpopped it shows in -malloc_dump
  PetscBool slepc;
  PetscCall(SlepcInitialized(&slepc));
  if (slepc) PetscCall(SlepcFinalize());
  PetscCall(PetscFinalize());
  return code;
}
