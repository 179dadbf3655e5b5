# ctest install.find_package_consumer: install ember's build into a fresh
# prefix, configure + build tests/install_consumer against it, run the program,
# and check that ember's private flags did not leak into the consumer's build.
# Inputs: EMBER_BUILD_DIR, EMBER_SOURCE_DIR, WORK_DIR, CONFIG.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(build ${WORK_DIR}/build)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

set(config_args)
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()
run("cmake --install" ${CMAKE_COMMAND} --install ${EMBER_BUILD_DIR} --prefix ${prefix} ${config_args})
foreach(f include/ember/boolean.hpp include/ember/io/mesh_io.hpp)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB_RECURSE config_files ${prefix}/*/emberConfig.cmake ${prefix}/*/emberConfigVersion.cmake)
list(LENGTH config_files n)
if(NOT n EQUAL 2)
  message(FATAL_ERROR "emberConfig.cmake and emberConfigVersion.cmake not both installed: ${config_files}")
endif()

run("configure the consumer" ${CMAKE_COMMAND} -S ${EMBER_SOURCE_DIR}/tests/install_consumer -B ${build}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
    -DEMBER_EXAMPLE_SOURCE=${EMBER_SOURCE_DIR}/docs/examples/cpp_api.cpp)
# Verbose, so the compile and link lines can be checked for ember's own flags.
run("build the consumer" ${CMAKE_COMMAND} --build ${build} --verbose)
foreach(flag -Wall -Wextra -Wpedantic -fsanitize)
  string(FIND "${last_output}" "${flag}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "ember's private flag ${flag} leaked into the consumer's build:\n${last_output}")
  endif()
endforeach()
run("run the consumer" ${build}/app ${WORK_DIR})
message(STATUS "consumer output:\n${last_output}")
