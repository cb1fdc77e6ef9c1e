# The same executables on two ranks: every test that creates PETSc objects
# then runs on a distributed layout (petsc-notes trap 1 shows up only there).
set(BOOMDYN_MPIEXEC ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 --oversubscribe --allow-run-as-root)
foreach(kind verification regression)
  if(TARGET ${kind}_tests)
    add_test(NAME mpi2.${kind} COMMAND ${BOOMDYN_MPIEXEC} $<TARGET_FILE:${kind}_tests>)
    set_tests_properties(mpi2.${kind} PROPERTIES LABELS "mpi;${kind}" PROCESSORS 2)
  endif()
endforeach()
