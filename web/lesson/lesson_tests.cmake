# The lesson page's tests, run by ctest: the parser, quote normalisation, math and the
# knowledge check's grading in node (web/test/lesson_parse.mjs, no WebAssembly), and the
# page served by `simlab lab` in headless Chromium (web/test/lesson_page_e2e.mjs; it
# reports "skipped" (77) without Chromium or web/node_modules, fails instead with
# SIMLAB_REQUIRE_BROWSER_TESTS, and saves its screenshots into the build folder).
find_program(SIMLAB_NODE node)
if(SIMLAB_NODE)
  add_test(NAME lesson_parse
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/lesson_parse.mjs
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  add_test(NAME lesson_page_e2e
           COMMAND ${SIMLAB_NODE} ${CMAKE_SOURCE_DIR}/web/test/lesson_page_e2e.mjs
                   --simlab $<TARGET_FILE:simlab> --out ${CMAKE_BINARY_DIR} ${SIMLAB_BROWSER_REQUIRE}
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(lesson_page_e2e PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180)
endif()
