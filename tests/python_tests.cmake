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

# benchmarks/plot_performance.py (the plots of docs/performance.md) on the
# recorded figures and on rows in benchmarks/run_scaling.py's --csv format.
add_test(NAME postprocess.plot_performance
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/postprocess/test_plot_performance.py
  WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
set_tests_properties(postprocess.plot_performance PROPERTIES LABELS postprocess)

# Scripts that run the boomdyn binary: SCRIPT BOOMDYN SOURCE_DIR BINARY_DIR.
function(boomdyn_script_test name script label)
  add_test(NAME ${name}
    COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/${script} $<TARGET_FILE:boomdyn> ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
  set_tests_properties(${name} PROPERTIES LABELS "${label}")
endfunction()

boomdyn_script_test(postprocess.frame_deflection postprocess/test_frame_deflection.py postprocess)
boomdyn_script_test(postprocess.frequency_check postprocess/test_frequency_check.py postprocess)
boomdyn_script_test(postprocess.stick_slip_scene postprocess/test_stick_slip_scene.py postprocess)
boomdyn_script_test(postprocess.snapshots postprocess/test_snapshots.py postprocess)
boomdyn_script_test(postprocess.paper_comparison_figures postprocess/test_paper_comparison.py postprocess)
boomdyn_script_test(postprocess.xdmf postprocess/test_xdmf.py postprocess)
boomdyn_script_test(postprocess.spatial_output postprocess/test_spatial_output.py postprocess)
boomdyn_script_test(postprocess.study postprocess/test_study.py postprocess)
boomdyn_script_test(postprocess.calibrate_paper postprocess/test_calibrate_paper.py postprocess)
boomdyn_script_test(regression.restart regression/test_restart.py "regression;mpi")
boomdyn_script_test(ts.options ts/test_ts_options.py ts)
set_tests_properties(regression.restart PROPERTIES PROCESSORS 2
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")

# Dependencies run one way (docs/architecture.md): no backward include
# between the layers; the self-test shows the check sees one.
add_test(NAME architecture.layers
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/architecture/check_layers.py ${CMAKE_SOURCE_DIR})
add_test(NAME architecture.layers_self_test
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/architecture/check_layers.py --self-test)
# What docs/architecture.md states about the code (size limit, layers,
# registered types) holds for the tree; the self-test doctors copies.
add_test(NAME architecture.doc_claims
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/architecture/check_doc_claims.py ${CMAKE_SOURCE_DIR})
add_test(NAME architecture.doc_claims_self_test
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/architecture/check_doc_claims.py --self-test ${CMAKE_SOURCE_DIR})
set_tests_properties(architecture.layers architecture.layers_self_test architecture.doc_claims
  architecture.doc_claims_self_test PROPERTIES LABELS architecture)
boomdyn_script_test(postprocess.output_channels postprocess/test_output_channels.py postprocess)
boomdyn_script_test(regression.help regression/test_help.py regression)
boomdyn_script_test(regression.option_values regression/test_option_values.py regression)
boomdyn_script_test(regression.damped_modal_output regression/test_damped_modal_output.py regression)
boomdyn_script_test(postprocess.hoist_output postprocess/test_hoist_output.py postprocess)

# A fresh clone's scripts/main.sh compiles boomdyn's sources and no test
# program (its build run as a dry run in a fresh copy of the tree; ~30 s).
add_test(NAME scripts.main_builds_boomdyn_only
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/scripts/test_main_build.py ${CMAKE_SOURCE_DIR}
          ${CMAKE_BINARY_DIR}/test_output/main_build)
set_tests_properties(scripts.main_builds_boomdyn_only PROPERTIES LABELS scripts TIMEOUT 600)

# README.md's and docs/options.md's option tables against `boomdyn -help`:
# every option exists, every default given as a value is the one -help
# prints; the self-test doctors the tables (tests/docs/check_options.py).
boomdyn_script_test(docs.options_match_help docs/check_options.py docs)
add_test(NAME docs.options_match_help_self_test
  COMMAND ${python} ${CMAKE_SOURCE_DIR}/tests/docs/check_options.py --self-test $<TARGET_FILE:boomdyn>
          ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/test_output/options_help)
set_tests_properties(docs.options_match_help_self_test PROPERTIES LABELS docs)

# docs/tutorial.md runs as written: its yaml blocks are docs/tutorial/boom.yaml,
# every command exits 0 and prints the numbers the page shows (1 and 2 ranks).
boomdyn_script_test(docs.tutorial docs/test_tutorial.py "docs;mpi")
set_tests_properties(docs.tutorial PROPERTIES PROCESSORS 2
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")
# Modal analysis and tracking of spatial scenes with the mode labels
# (closed forms, 2 ranks, -boom_spatial; docs/model.md §5).
boomdyn_script_test(regression.spatial_modal regression/test_spatial_modal.py "regression;mpi")
set_tests_properties(regression.spatial_modal PROPERTIES PROCESSORS 2
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")
