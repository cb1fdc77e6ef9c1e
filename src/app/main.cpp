// boomdyn: flexible multibody dynamics of planar telescopic crane booms.
//
//   boomdyn SCENE.yaml [-o OUT.h5] [-boom_overwrite] [-boom_quiet] [PETSc options]
//
// Reads a scene (docs/scenes.md), runs its static, dynamic or modal
// analysis and writes an HDF5 results file (docs/output.md). This file is
// the error reporting; options.cpp reads the options, run.cpp builds the
// Simulation (include/boomdyn/simulation.hpp).
#include "options.hpp"
#include "out_of_memory.hpp"
#include "run.hpp"
#include "signals.hpp"

#include "boomdyn/newton_solver.hpp"
#include "boomdyn/scene_reader.hpp"
#include "boomdyn/singleton_start.hpp"

#include <slepcsys.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <thread>
#include <vector>

static const char help[] = "boomdyn SCENE.yaml [-o OUT.h5] [-boom_overwrite] [-boom_quiet] [boomdyn and PETSc options]\n"
                           "(boomdyn -help lists every option with its default; docs/options.md describes them)\n";

namespace {

// PETSc errors (a failed factorization, a bad option value, a bad scene
// reported by the io layer through PetscCallCXX, ...) are reported as one
// line naming the scene, like every other error, instead of PETSc's
// traceback and an MPI_Abort: the handler keeps the first message and lets
// the error code travel up to main.
std::string firstPetscError;
PetscErrorCode firstPetscErrorCode = 0;

PetscErrorCode keepFirstError(MPI_Comm, int line, const char *function, const char *file, PetscErrorCode n,
                              PetscErrorType type, const char *message, void *)
{
  if (type == PETSC_ERROR_INITIAL && firstPetscError.empty()) {
    const char *text = nullptr;
    PetscErrorMessage(n, &text, nullptr);
    firstPetscError = message && *message ? message : (text ? text : "PETSc error");
    // PETSc 3.18's allocator reports a failed malloc with the caller's line
    // as the error code: it is known by where it arose.
    const bool allocation = n == PETSC_ERR_MEM || (function && std::string(function) == "PetscMallocAlign");
    firstPetscErrorCode = allocation ? PETSC_ERR_MEM : n;
    // User errors (bad options, scene, model; the io layer's exceptions,
    // which cross into PETSc code in src/app and src/simulation) say all
    // there is to say; other errors name where they arose.
    const std::string where = file ? file : "?";
    const bool userError = n == PETSC_ERR_USER_INPUT || n == PETSC_ERR_NOT_CONVERGED ||
                           n == PETSC_ERR_FILE_WRITE || // a full disk, a results file taken by another run
                           where.find("src/app/") != std::string::npos || where.find("src/simulation/") != std::string::npos;
    if (!userError)
      firstPetscError += " (in " + std::string(function ? function : "?") + ", " + where + ":" + std::to_string(line) + ")";
  }
  return n;
}

// Messages that do not say which scene they are about get its name.
std::string aboutScene(const std::string &message, const std::string &scene)
{
  return scene.empty() || message.find(scene) != std::string::npos ? message : scene + ": " + message;
}

// The line that tells the user why the run failed.
std::string errorLine(const std::string &scene)
{
  std::string message = firstPetscError;
  if (firstPetscErrorCode == PETSC_ERR_MEM) // with where it happened, which may help
    message = boomdyn::outOfMemoryMessage(boomdyn::petscRequestedBytes(firstPetscError)) + " (at: " + message + ")";
  else if (message.find("std::bad_alloc") != std::string::npos) // through PetscCallCXX
    message = boomdyn::outOfMemoryMessage(boomdyn::lastFailedAllocation());
  return "boomdyn: error: " + aboutScene(message, scene);
}

// Every rank ends here, with its error line (empty: success). An error that
// only some ranks met leaves the others waiting in a collective call
// forever: a failing rank that does not see the others arrive within
// -boom_error_wait seconds prints its own message and aborts the job. When
// all arrive, rank 0 prints its message, or the first failing rank prints
// its own if rank 0 has none, and all exit with the largest code.
PetscErrorCode reportTogether(const std::string &line, double wait, int *code)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (size == 1) {
    if (!line.empty()) PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s\n", line.c_str()));
    PetscFunctionReturn(0);
  }
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

// Options, scene, run. A failed or interrupted run sets line and code; its
// results file is complete up to that point and says so in /summary.
PetscErrorCode runProgram(int argc, char **argv, boomdyn::AppOptions *opts, std::string *line, int *code)
{
  std::unique_ptr<boomdyn::Scene> scene;
  PetscFunctionBeginUser;
  PetscCall(boomdyn::sceneArgument(argc, argv, &opts->scenePath));
  PetscCall(boomdyn::rejectStrayArguments(argc, argv));
  std::vector<std::string> given;
  PetscCall(boomdyn::userOptionNames(&given));
  // Scene errors (file, line, key) are reported by the reader by exception.
  if (!opts->scenePath.empty())
    PetscCallCXX(scene = std::make_unique<boomdyn::Scene>(boomdyn::readSceneFile(opts->scenePath)));
  PetscCall(boomdyn::readAppOptions(scene.get(), opts));
  if (!scene && opts->help) { // the solvers' options too, with their defaults
    boomdyn::JacobianReuse reuse;
    PetscBool schur = PETSC_FALSE;
    PetscCall(boomdyn::readNewtonOptions(PETSC_COMM_WORLD, nullptr, &reuse, &schur));
    PetscFunctionReturn(0);
  }
  PetscCheck(scene, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
             "usage: boomdyn SCENE.yaml [-o OUT.h5] [-boom_overwrite] [-boom_quiet] [PETSc options]; see README.md and docs/options.md "
             "(boomdyn -help lists every option)");
  PetscCall(boomdyn::rejectUnknownOptions(scene.get()));
  PetscCall(boomdyn::checkRunFiles(*opts, scene->analysis == boomdyn::Scene::Analysis::Dynamic));
  if (opts->partitionReport) PetscFunctionReturn(boomdyn::reportPartitions(*scene, opts->partitionParts));
  boomdyn::installInterruptHandlers();
  boomdyn::RunOutcome outcome;
  PetscCall(boomdyn::runScene(*scene, *opts, argc, argv, &outcome));
  // Options nobody read (-ksp_typo, -modal_eps_nev on a dynamic run) were ignored: say so.
  std::string unused;
  PetscCall(boomdyn::reportUnusedOptions(given, &unused));
  if (!unused.empty())
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "boomdyn: warning: %s: options not used by this run: %s\n",
                          scene->file.c_str(), unused.c_str()));
  if (outcome.interrupted()) {
    *line = "boomdyn: run interrupted at t = " + std::to_string(outcome.endTime) + " s by signal " +
            std::to_string(boomdyn::interruptSignal()) + "; results so far in " + opts->outputPath +
            (outcome.dynamic ? ", continue with -boom_restart " + opts->checkpointPath : std::string());
    *code = 128 + boomdyn::interruptSignal();
  } else if (!outcome.completed()) {
    *line = "boomdyn: error: " + scene->file + ": run " + outcome.status + " (results so far in " + opts->outputPath + ")";
    *code = 1;
  }
  PetscFunctionReturn(0);
}

} // namespace

int main(int argc, char **argv)
{
  const boomdyn::SingletonStart singleton; // before MPI_Init, released after MPI_Finalize
  if (const std::string missing = boomdyn::unreadableOptionsFile(argc, argv); !missing.empty()) {
    std::printf("boomdyn: error: %s\n", missing.c_str());
    return 1;
  }
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  PetscCall(PetscPushErrorHandler(keepFirstError, nullptr));
  boomdyn::AppOptions opts;
  std::string line;
  int code = 0;
  PetscErrorCode failed;
  // C++ exceptions that no PetscCallCXX turned into an error code (a
  // std::bad_alloc in the Jacobian pattern of a mesh too large for the
  // address space) end here, not in std::terminate (exit 134, no message).
  try {
    failed = runProgram(argc, argv, &opts, &line, &code);
  } catch (const std::bad_alloc &) {
    failed = PETSC_ERR_MEM;
    firstPetscError = boomdyn::outOfMemoryMessage(boomdyn::lastFailedAllocation());
    firstPetscErrorCode = 0;
  } catch (const std::exception &e) {
    failed = PETSC_ERR_LIB;
    if (firstPetscError.empty()) firstPetscError = std::string("internal error: ") + e.what();
  }
  if (failed) {
    line = errorLine(opts.scenePath);
    code = 1;
  }
  PetscCall(reportTogether(line, opts.errorWait, &code));
  PetscCall(PetscPopErrorHandler()); // pushed above; unpopped it shows in -malloc_dump
  PetscBool slepc;
  PetscCall(SlepcInitialized(&slepc));
  if (slepc) PetscCall(SlepcFinalize());
  PetscCall(PetscFinalize());
  return code;
}
