# Writes the version header at build time (run by the boomdyn_version target
# on every build, see CMakeLists.txt):
#   cmake -DSOURCE_DIR=... -DOUTPUT=.../version.hpp -DINPUT=src/app/version.hpp.in
#         -DPROJECT_VERSION=x.y.z -DBOOMDYN_ISA=x86-64-v3 -DGIT_EXECUTABLE=/usr/bin/git -P cmake/boomdyn_version.cmake
# The commit comes from `git describe --always --dirty --tags`, so a build
# from a tree with uncommitted changes says "-dirty", and a commit after the
# last configure is seen. configure_file rewrites OUTPUT only when its text
# changes, so an unchanged version recompiles nothing.
set(BOOMDYN_GIT "unknown")
if(GIT_EXECUTABLE)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty --tags
    WORKING_DIRECTORY ${SOURCE_DIR} OUTPUT_VARIABLE described RESULT_VARIABLE failed
    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT failed AND described)
    set(BOOMDYN_GIT "${described}")
  endif()
endif()
configure_file(${INPUT} ${OUTPUT} @ONLY)
