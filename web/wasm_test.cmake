# The WebAssembly build's tests, run by the native ctest against the native simlab:
# rollouts in node (web/test/rollout_equivalence.mjs) and in headless Chromium
# (web/test/browser_equivalence.mjs). They report "skipped" (exit 77) with the reason
# when web/dist is missing (no emscripten, or tools/build_wasm.sh not run) or older than
# the sources, or when Chromium / web/node_modules are missing (with
# SIMLAB_REQUIRE_BROWSER_TESTS: they fail instead).
find_program(SIMLAB_NODE node)
if(SIMLAB_NODE)
  foreach(wasm_test rollout_equivalence browser_equivalence)
    add_test(NAME wasm_${wasm_test}
             COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/${wasm_test}.mjs
                     --simlab $<TARGET_FILE:simlab> --dist ${CMAKE_SOURCE_DIR}/web/dist
                     ${SIMLAB_BROWSER_REQUIRE}
             WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
    set_tests_properties(wasm_${wasm_test} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
  endforeach()
endif()
