# Install and export: `cmake --install build --prefix PREFIX` puts
#
#   PREFIX/bin/simlab                            the command line
#   PREFIX/include/simlab/*.h                    the public API
#   PREFIX/lib/libsimlab_core.a                  the engine (static)
#   PREFIX/lib/cmake/simlab/simlab*.cmake        the CMake package
#
# so that another project needs only `find_package(simlab REQUIRED)` and
# `target_link_libraries(app PRIVATE simlab::simlab)` (CMAKE_PREFIX_PATH=PREFIX if PREFIX
# is not a system prefix). The package is relocatable: nothing in it names the build or
# the source tree (tests/install/run_install_test.sh checks that). Native builds only:
# the browser build has nothing to install.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(SIMLAB_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/simlab)

# Outside the tree the engine is simlab::simlab; inside it stays simlab_core (the alias
# lets a project that adds this one as a subdirectory use the installed name too).
set_target_properties(simlab_core PROPERTIES EXPORT_NAME simlab)
add_library(simlab::simlab ALIAS simlab_core)
# The public headers use C++20 (std::span): a consumer that sets no standard gets it
# from the target (the tree itself sets CMAKE_CXX_STANDARD 20 for everything).
target_compile_features(simlab_core PUBLIC cxx_std_20)

install(TARGETS simlab_core EXPORT simlabTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/simlab
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(TARGETS simlab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(EXPORT simlabTargets
        NAMESPACE simlab::
        FILE simlabTargets.cmake
        DESTINATION ${SIMLAB_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/simlabConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/cmake/simlabConfig.cmake
                              INSTALL_DESTINATION ${SIMLAB_INSTALL_CMAKEDIR})
# SameMajorVersion rather than AnyNewerVersion: find_package(simlab 0.14) accepts 0.14
# and any later 0.x but refuses a 1.x, since a new major version is where the API (which
# follows MuJoCo's names and shapes) may break, and a clear "version not compatible" at
# configure time beats compile errors in the consumer. (Before 1.0 a minor release may
# still change the API; whoever needs one exact API can ask for it with EXACT.)
# Not ARCH_INDEPENDENT: the library is compiled code, so a 32-bit consumer must not pick
# up a 64-bit build.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/simlabConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/simlabConfig.cmake
              ${CMAKE_BINARY_DIR}/cmake/simlabConfigVersion.cmake
        DESTINATION ${SIMLAB_INSTALL_CMAKEDIR})
