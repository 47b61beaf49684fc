# The Python package's tests (pytest, Debian's python3-pytest), one ctest entry per test
# file so that ctest -j runs them side by side. They use the package in build/python, the
# `simlab` command and the lesson's C++ example of the same build.
if(TARGET _simlab)
  file(GLOB SIMLAB_PYTHON_TESTS CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/python/tests/test_*.py)
  # test_rollout_equivalence steps every conformance case twice (the command line and
  # Python): three entries, each a third of the cases (SIMLAB_TEST_SHARD=k/3), so that
  # the sanitizer build (some 380 s for all of them) runs them side by side, each well
  # inside its timeout.
  set(environment "PYTHONPATH=${CMAKE_BINARY_DIR}/python;SIMLAB_BUILD_DIR=${CMAKE_BINARY_DIR}")
  foreach(test_file ${SIMLAB_PYTHON_TESTS})
    get_filename_component(test_name ${test_file} NAME_WE)
    set(command ${SIMLAB_PYTHON_EXECUTABLE} -m pytest -p no:cacheprovider -q ${test_file})
    if(test_name STREQUAL "test_rollout_equivalence")
      foreach(shard 0 1 2)
        add_test(NAME python_${test_name}_${shard}of3 COMMAND ${command}
                 WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
        set_tests_properties(python_${test_name}_${shard}of3 PROPERTIES
                             ENVIRONMENT "${environment};SIMLAB_TEST_SHARD=${shard}/3" TIMEOUT 600)
      endforeach()
    else()
      add_test(NAME python_${test_name} COMMAND ${command} WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
      set_tests_properties(python_${test_name} PROPERTIES ENVIRONMENT "${environment}" TIMEOUT 600)
    endif()
  endforeach()
endif()
