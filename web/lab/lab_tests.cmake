# The lab's tests, run by ctest: the expression parser and lab-block reader in node
# (web/test/lab_expr.mjs, no WebAssembly), and the lab end to end in headless Chromium on
# the lesson page served by `simlab lab` (web/test/lab_e2e.mjs: the lab against its block,
# toggles, sliders, readouts, real time, readouts equal to the native `simlab rollout`;
# screenshots saved in the build folder's lab_screenshots). The browser test reports
# "skipped" (77) with the reason when web/dist is missing or older than the sources, or
# Chromium / web/node_modules are missing; with SIMLAB_REQUIRE_BROWSER_TESTS it fails.
find_program(SIMLAB_NODE node)
if(SIMLAB_NODE)
  add_test(NAME lab_expr
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/lab_expr.mjs
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  # The lab's model file finder in node (web/lab/model_files.mjs), and the fixture with its
  # STL mesh compiled by the WebAssembly build when web/dist exists; its convex hulls
  # against MuJoCo's goldens and a colliding-mesh rollout against the native simlab.
  add_test(NAME lab_model_files
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/model_files.mjs
                   --dist ${CMAKE_SOURCE_DIR}/web/dist --simlab $<TARGET_FILE:simlab>
                   ${SIMLAB_BROWSER_REQUIRE}
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  add_test(NAME lab_e2e
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/lab_e2e.mjs
                   --simlab $<TARGET_FILE:simlab> --dist ${CMAKE_SOURCE_DIR}/web/dist
                   --shots ${CMAKE_BINARY_DIR}/lab_screenshots ${SIMLAB_BROWSER_REQUIRE}
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(lab_e2e PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 RUN_SERIAL TRUE)
  # The viewer's parts that need no browser (generated panels, pacer, model files given
  # by the user), in node; then `simlab view` on MuJoCo's own models in headless Chromium
  # (web/test/view_e2e.mjs: pictures, generated sliders, simulate's keys, picked plots,
  # CSV and PNG exports; screenshots in the build folder's view_screenshots).
  add_test(NAME view_units
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/view_units.mjs
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  add_test(NAME view_e2e
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/view_e2e.mjs
                   --simlab $<TARGET_FILE:simlab> --dist ${CMAKE_SOURCE_DIR}/web/dist
                   --shots ${CMAKE_BINARY_DIR}/view_screenshots ${SIMLAB_BROWSER_REQUIRE}
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(view_e2e PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 RUN_SERIAL TRUE)
endif()
