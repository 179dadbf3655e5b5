# `cmake --install` puts the headers, the layer libraries and an exported
# package (emberConfig.cmake + version file) under the prefix, so a consumer
# writes find_package(ember REQUIRED) and links ember::ember.
#
# What travels to consumers is only the usage requirements the headers need:
# the include directory, TBB (the core's threads, tbbmalloc for polygon
# buffers) and lib3mf (the static io layer's 3MF support). ember's warning and
# sanitizer flags stay behind: warnings are linked as BUILD_INTERFACE and the
# sanitizer flags are directory options, not target properties.
include(CMakePackageConfigHelpers)

set(EMBER_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/ember CACHE STRING "Where emberConfig.cmake is installed")

set(_ember_install_targets ember ember_numbers ember_geometry ember_core ember_io)
install(TARGETS ${_ember_install_targets} EXPORT emberTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/ember DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT emberTargets NAMESPACE ember:: DESTINATION ${EMBER_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/emberConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/emberConfig.cmake INSTALL_DESTINATION ${EMBER_INSTALL_CMAKEDIR})
# 0.x: only the same minor version is compatible.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/emberConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/emberConfig.cmake ${CMAKE_BINARY_DIR}/emberConfigVersion.cmake
              ${CMAKE_SOURCE_DIR}/cmake/Findlib3mf.cmake DESTINATION ${EMBER_INSTALL_CMAKEDIR})

# The test: install into a fresh prefix, then configure, build and run the
# consumer in tests/install_consumer (which compiles docs/examples/cpp_api.cpp).
# A sanitized static library needs the sanitizer runtime in the consumer's
# link, so this runs in the plain build only.
if(EMBER_BUILD_TESTS AND NOT EMBER_SANITIZE)
  add_test(NAME install.find_package_consumer
           COMMAND ${CMAKE_COMMAND} -DEMBER_BUILD_DIR=${CMAKE_BINARY_DIR} -DEMBER_SOURCE_DIR=${CMAKE_SOURCE_DIR}
                   -DWORK_DIR=${CMAKE_BINARY_DIR}/install-consumer-test -DCONFIG=$<CONFIG>
                   -P ${CMAKE_SOURCE_DIR}/tests/install_consumer/run_test.cmake)
  set_tests_properties(install.find_package_consumer PROPERTIES TIMEOUT 600)
endif()
