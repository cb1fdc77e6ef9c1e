# Tests of the Python postprocessing tools (postprocess/). Included from
# tests/CMakeLists.txt.
#
# They need numpy, h5py and matplotlib. The first python3 on PATH need not
# have them (a pyenv or virtualenv shim often does not, while Debian's
# /usr/bin/python3 with python3-h5py and python3-matplotlib does), so the
# first interpreter that imports all three is used; set BOOMDYN_PYTHON to
# choose another.
set(BOOMDYN_PYTHON "" CACHE FILEPATH "Python 3 with numpy, h5py and matplotlib, for the postprocess tests")
if(NOT BOOMDYN_PYTHON)
  find_program(BOOMDYN_PYTHON_ON_PATH NAMES python3)
  foreach(candidate ${BOOMDYN_PYTHON_ON_PATH} /usr/bin/python3)
    execute_process(COMMAND ${candidate} -c "import numpy, h5py, matplotlib"
      RESULT_VARIABLE missing OUTPUT_QUIET ERROR_QUIET)
    if(missing EQUAL 0)
      set(BOOMDYN_PYTHON ${candidate} CACHE FILEPATH
        "Python 3 with numpy, h5py and matplotlib, for the postprocess tests" FORCE)
      break()
    endif()
  endforeach()
endif()
if(NOT BOOMDYN_PYTHON)
  # Registered anyway: the test then fails on the missing module, visibly.
  message(WARNING "No python3 with numpy, h5py and matplotlib found; postprocess tests will fail. "
    "On Debian: apt-get install python3-h5py python3-matplotlib")
  set(python python3)
else()
  set(python ${BOOMDYN_PYTHON})
endif()

add_test(NAME postprocess.plot_run
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/postprocess/test_plot_run.py
  WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
set_tests_properties(postprocess.plot_run PROPERTIES LABELS postprocess)

add_test(NAME postprocess.frame_deflection
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/postprocess/test_frame_deflection.py $<TARGET_FILE:boomdyn>
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(postprocess.frame_deflection PROPERTIES LABELS postprocess)

add_test(NAME postprocess.frequency_check
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/postprocess/test_frequency_check.py $<TARGET_FILE:boomdyn>
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(postprocess.frequency_check PROPERTIES LABELS postprocess)

add_test(NAME postprocess.stick_slip_scene
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/postprocess/test_stick_slip_scene.py $<TARGET_FILE:boomdyn>
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(postprocess.stick_slip_scene PROPERTIES LABELS postprocess)

add_test(NAME regression.restart
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/regression/test_restart.py $<TARGET_FILE:boomdyn>
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(regression.restart PROPERTIES LABELS "regression;mpi" PROCESSORS 2
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")

add_test(NAME postprocess.snapshots
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/postprocess/test_snapshots.py $<TARGET_FILE:boomdyn>
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(postprocess.snapshots PROPERTIES LABELS postprocess)

add_test(NAME postprocess.paper_comparison_figures
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/postprocess/test_paper_comparison.py $<TARGET_FILE:boomdyn>
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(postprocess.paper_comparison_figures PROPERTIES LABELS postprocess)

add_test(NAME postprocess.xdmf
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/postprocess/test_xdmf.py $<TARGET_FILE:boomdyn>
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(postprocess.xdmf PROPERTIES LABELS postprocess)
