# The same executables on two ranks: every test that creates PETSc objects
# then runs on a distributed layout (docs/petsc-notes.md trap 1 shows up only there).
set(BOOMDYN_MPIEXEC ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 --oversubscribe --allow-run-as-root)
foreach(kind verification regression)
  if(TARGET ${kind}_tests)
    add_test(NAME mpi2.${kind} COMMAND ${BOOMDYN_MPIEXEC} $<TARGET_FILE:${kind}_tests>)
    set_tests_properties(mpi2.${kind} PROPERTIES LABELS "mpi;${kind}" PROCESSORS 2)
  endif()
endforeach()

# An error on one rank only (injected) must not hang the job: the failing
# rank waits -boom_error_wait seconds for the others, then reports its own
# message and aborts. TIMEOUT catches a hang.
foreach(failing 0 1)
  add_test(NAME mpi2.rank_local_error_${failing}
    COMMAND ${BOOMDYN_MPIEXEC} -x BOOMDYN_TEST_FAIL_RANK=${failing} $<TARGET_FILE:boomdyn>
            ${CMAKE_SOURCE_DIR}/inputs/cantilever_dynamic.yaml -o ${CMAKE_BINARY_DIR}/test_output/rank_error_${failing}.h5
            -boom_overwrite -boom_quiet -boom_error_wait 2)
  set_tests_properties(mpi2.rank_local_error_${failing} PROPERTIES LABELS mpi PROCESSORS 2 TIMEOUT 60
    PASS_REGULAR_EXPRESSION "failure injected on rank ${failing}.*rank ${failing} failed alone and the other ranks cannot finish without it; aborting")
endforeach()
