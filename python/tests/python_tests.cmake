# The Python package's tests (pytest, Debian's python3-pytest), one ctest entry per test
# file so that ctest -j runs them side by side. They use the package in build/python, the
# `simlab` command and the lesson's C++ example of the same build.
if(TARGET _simlab)
  file(GLOB SIMLAB_PYTHON_TESTS CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/python/tests/test_*.py)
  foreach(test_file ${SIMLAB_PYTHON_TESTS})
    get_filename_component(test_name ${test_file} NAME_WE)
    add_test(NAME python_${test_name}
             COMMAND ${SIMLAB_PYTHON_EXECUTABLE} -m pytest -p no:cacheprovider -q ${test_file}
             WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
    set_tests_properties(python_${test_name} PROPERTIES
                         ENVIRONMENT "PYTHONPATH=${CMAKE_BINARY_DIR}/python;SIMLAB_BUILD_DIR=${CMAKE_BINARY_DIR}"
                         TIMEOUT 600)
  endforeach()
endif()
