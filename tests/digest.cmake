# Regression digests (issue 12): every scene in inputs/ runs with default
# options on one rank and its digest (final state norms, sensors at five
# times, frequencies, events, step counts; tests/regression/digest.py) must
# match the stored one in tests/regression/digests/<scene>.digest.
# Included from tests/CMakeLists.txt; docs/verification.md, "Regression digests".
#
# After an intended change of results:
#   BOOMDYN_DIGEST_UPDATE=1 ctest --test-dir build -L digest
# rewrites the stored digests; the commit must say which numbers moved and by how much.

set(digest_script ${CMAKE_SOURCE_DIR}/tests/regression/digest.py)
set(digest_dir ${CMAKE_SOURCE_DIR}/tests/regression/digests)
set(digest_out ${CMAKE_BINARY_DIR}/test_output/digest)
file(MAKE_DIRECTORY ${digest_out})

file(GLOB digest_scenes CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/inputs/*.yaml)
foreach(scene ${digest_scenes})
  get_filename_component(stem ${scene} NAME_WE)
  add_test(NAME digest.${stem}
    COMMAND /usr/bin/python3 ${digest_script} ${digest_out}/${stem}.h5 ${digest_dir}/${stem}.digest
            --boomdyn $<TARGET_FILE:boomdyn> --scene ${scene})
  set_tests_properties(digest.${stem} PROPERTIES LABELS digest TIMEOUT 300)
endforeach()

# The comparison catches a real change: the same scenes with one option
# changed must be reported as different (not merely fail: the output must
# name the mismatch). --never-update keeps BOOMDYN_DIGEST_UPDATE=1 from
# storing the changed run.
function(digest_must_differ name stem options)
  add_test(NAME digest.detects_${name}
    COMMAND /usr/bin/python3 ${digest_script} ${digest_out}/${stem}_${name}.h5 ${digest_dir}/${stem}.digest
            --boomdyn $<TARGET_FILE:boomdyn> --scene ${CMAKE_SOURCE_DIR}/inputs/${stem}.yaml
            --args "${options}" --never-update)
  set_tests_properties(digest.detects_${name} PROPERTIES LABELS digest TIMEOUT 300
    PASS_REGULAR_EXPRESSION "digest: .* differs from .*${stem}\\.digest in [0-9]+ of [0-9]+ values")
endfunction()
digest_must_differ(rho_inf_change cantilever_dynamic "-boom_rho_inf 0.79")
digest_must_differ(step_change flexible_pendulum "-ts_dt 0.0009")
digest_must_differ(mesh_change cantilever_modal "-boom_elements 17")
digest_must_differ(spatial_mesh_change spatial_boom_side_load "-boom_elements 9") # spatial beams take -boom_elements too

# The comparison rules themselves, on hand-made digests (no run).
add_test(NAME digest.script COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/regression/test_digest.py)
set_tests_properties(digest.script PROPERTIES LABELS digest)
