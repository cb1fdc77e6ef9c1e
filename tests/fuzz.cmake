# Robustness tests (GitHub issue 8); included at the end of tests/CMakeLists.txt.
#
# fuzz.dictionary_covers_keys  its dictionary names every scene key (check_dictionary.py).
# fuzz.scene_parser   libFuzzer on the scene reader for 60 s (clang++, ASan + UBSan),
#                     built outside this (g++) project by tests/fuzz/run_fuzzer.sh into
#                     ${CMAKE_BINARY_DIR}/fuzz; SKIPPED when there is no clang++.
# bad_model.<case>    each scene in tests/bad_model/ is refused cleanly by boomdyn
#                     (tests/bad_model/run_bad_models.py on that one file).
# bad_input.<case>    each file in tests/bad_input/ is refused cleanly by the boomdyn
#                     program, checked by the same runner (the reader's own message is
#                     also checked in-process by the unit test
#                     SceneReaderFiles.EveryBadInputIsRejectedAsAnnounced).
# See docs/reliability.md.

add_test(NAME fuzz.scene_parser
  COMMAND bash ${CMAKE_SOURCE_DIR}/tests/fuzz/run_fuzzer.sh ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties(fuzz.scene_parser PROPERTIES
  LABELS fuzz SKIP_RETURN_CODE 77 TIMEOUT 600
  PROCESSORS 1) # one fuzzing process (FUZZ_JOBS=n for more, outside CTest)
# The fuzzer's dictionary names every scene key (schema tables, inputs/, seeds).
add_test(NAME fuzz.dictionary_covers_keys
  COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/fuzz/check_dictionary.py ${CMAKE_SOURCE_DIR})
set_tests_properties(fuzz.dictionary_covers_keys PROPERTIES LABELS fuzz TIMEOUT 60)

# ASan reserves terabytes of address space, so a sanitizer build cannot run under the
# runner's address-space limit (--mem-mb); ASan's own RSS limit takes its place, and leaks
# of the aborted runs are not reported (the corpus is about messages, not memory).
set(bad_model_args "")
set(bad_model_env "")
if(BOOMDYN_SANITIZE)
  set(bad_model_args --mem-mb 0)
  set(bad_model_env "ASAN_OPTIONS=detect_leaks=0:hard_rss_limit_mb=4096")
endif()
# One CTest per case, so that `ctest -R bad_model.` lists failures by name and
# `ctest -R bad_model.slider_beyond_track` reruns one.
foreach(kind bad_model bad_input)
  file(GLOB cases CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/${kind}/*.yaml)
  foreach(case ${cases})
    get_filename_component(stem ${case} NAME_WE)
    add_test(NAME ${kind}.${stem}
      COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/bad_model/run_bad_models.py
              --boomdyn $<TARGET_FILE:boomdyn> ${bad_model_args} ${case})
    set_tests_properties(${kind}.${stem} PROPERTIES LABELS ${kind} TIMEOUT 120)
    if(bad_model_env)
      set_tests_properties(${kind}.${stem} PROPERTIES ENVIRONMENT "${bad_model_env}")
    endif()
  endforeach()
endforeach()

# A small file system for the full-disk cases where no tmpfs may be mounted:
# preloaded into boomdyn, it fakes statvfs() and ENOSPC in one folder.
add_library(small_disk_shim MODULE ${CMAKE_SOURCE_DIR}/tests/faults/small_disk_shim.c)
target_link_libraries(small_disk_shim PRIVATE ${CMAKE_DL_LIBS})

# Faults injected into real runs (issue 17; tests/faults/run_fault.py): one
# CTest per case, faults.<case>. Exit 77 (no tmpfs mount allowed, no mpiexec)
# is a skip, with the reason in the output.
set(fault_cases
  state_interval_tiny checkpoint_interval_tiny tracking_interval_tiny too_many_steps static_sigterm static_sigint
  modal_sigint modal_sigterm tracking_sigterm
  sighup_1 sighup_2 sigpipe_1 sigpipe_2
  output_is_scene output_is_checkpoint_or_restart concurrent_overwrite concurrent_overwrite_unlocked
  full_disk_results full_disk_checkpoint full_disk_results_shim full_disk_checkpoint_shim full_disk_results_2
  restart_nan_time restart_violated_state restart_options_mismatch
  special_file_outputs out_of_memory restart_edited_state restart_formulation_mismatch full_disk_status_shim
  second_scene unused_option private_session_dir memory_estimate)
foreach(case ${fault_cases})
  add_test(NAME faults.${case}
    COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/faults/run_fault.py $<TARGET_FILE:boomdyn> ${CMAKE_SOURCE_DIR}
            ${CMAKE_BINARY_DIR} ${case} ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 --oversubscribe --allow-run-as-root)
  set_tests_properties(faults.${case} PROPERTIES LABELS faults TIMEOUT 180 SKIP_RETURN_CODE 77
    ENVIRONMENT "BOOMDYN_SMALL_DISK_SHIM=$<TARGET_FILE:small_disk_shim>")
endforeach()
set_tests_properties(faults.sighup_2 faults.sigpipe_2 faults.full_disk_results_2 PROPERTIES PROCESSORS 2)
