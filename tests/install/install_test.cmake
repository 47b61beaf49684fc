# install_find_package: install this build into a fresh prefix in the build tree, build
# tests/install/consumer (a project outside the tree: find_package(simlab), simlab::simlab)
# against that prefix only, run it on the actuator bench and check what it prints
# (tests/install/run_install_test.sh). Needs simlab_core and simlab built.
add_test(NAME install_find_package
         COMMAND bash ${CMAKE_SOURCE_DIR}/tests/install/run_install_test.sh
                 ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR} ${CMAKE_COMMAND} "${CMAKE_GENERATOR}"
                 ${CMAKE_CXX_COMPILER} $<CONFIG>)
set_tests_properties(install_find_package PROPERTIES TIMEOUT 300)
