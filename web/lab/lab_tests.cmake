# The lab's tests, run by ctest: the expression parser and lab-block reader in node
# (web/test/lab_expr.mjs, no WebAssembly), and the lab end to end in headless Chromium
# (web/test/lab_e2e.mjs: sliders, readouts, real time, readouts equal to the native
# `simlab rollout`; screenshots saved in the build folder's lab_screenshots). The
# browser test reports "skipped" (77) with the reason when web/dist is missing or older
# than the sources, or Chromium / web/node_modules are missing.
find_program(SIMLAB_NODE node)
if(SIMLAB_NODE)
  add_test(NAME lab_expr
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/lab_expr.mjs
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  add_test(NAME lab_e2e
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/lab_e2e.mjs
                   --simlab $<TARGET_FILE:simlab> --dist ${CMAKE_SOURCE_DIR}/web/dist
                   --shots ${CMAKE_BINARY_DIR}/lab_screenshots
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(lab_e2e PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 RUN_SERIAL TRUE)
endif()
