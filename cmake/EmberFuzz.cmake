# Fuzz targets for the readers (tests/fuzz): one per format.
#
# Every test build compiles each target with a replay driver and runs it over
# a seed corpus (small files of /work/shared/data's layout, ../shared/data
# beside the source tree, and docs/examples): ctest fuzz.<format>.replay, which
# is skipped when the data is absent.
#
# -DEMBER_FUZZ=ON (clang only) also builds the libFuzzer executables
# ember_fuzz_<format> with -fsanitize=fuzzer,address,undefined and adds
# fuzz.<format>.smoke, a 2-second libFuzzer run on that corpus. A GCC build
# does the same in a clang sub-build when clang++ links libFuzzer
# (EMBER_FUZZ_AUTO); otherwise fuzz.libfuzzer is reported as skipped. Longer runs:
#   tests/fuzz/run.sh build-fuzz/bin/ember_fuzz_obj obj 180 /tmp/fuzz-obj ../shared/data
option(EMBER_FUZZ "Build the libFuzzer reader targets (needs clang)" OFF)
if(NOT EMBER_BUILD_TESTS)
  return()
endif()
set(_ember_fuzz_formats obj stl ply off 3mf gltf glb)
set(_ember_fuzz_seeds ${CMAKE_SOURCE_DIR}/../shared/data ${CMAKE_SOURCE_DIR}/docs/examples)

foreach(fmt ${_ember_fuzz_formats})
  add_executable(ember_fuzz_replay_${fmt} ${CMAKE_SOURCE_DIR}/tests/fuzz/fuzz_${fmt}.cpp
                                          ${CMAKE_SOURCE_DIR}/tests/fuzz/replay_main.cpp)
  target_include_directories(ember_fuzz_replay_${fmt} PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_compile_definitions(ember_fuzz_replay_${fmt} PRIVATE EMBER_FUZZ_EXT=".${fmt}")
  target_link_libraries(ember_fuzz_replay_${fmt} PRIVATE ember ember_warnings)
  add_test(NAME fuzz.${fmt}.replay COMMAND ember_fuzz_replay_${fmt} ${_ember_fuzz_seeds})
  set_tests_properties(fuzz.${fmt}.replay PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
endforeach()

if(NOT EMBER_FUZZ)
  # A GCC build builds the libFuzzer targets in a clang sub-build (build/fuzz/)
  # when clang++ can link -fsanitize=fuzzer, so the suite's smoke runs happen
  # wherever they can. The sanitized pass (EMBER_SANITIZE) leaves them to the
  # plain one.
  option(EMBER_FUZZ_AUTO "Build the libFuzzer targets with clang++ in a sub-build when it can" ON)
  set(_ember_fuzz_sub OFF)
  if(EMBER_FUZZ_AUTO AND NOT EMBER_SANITIZE)
    find_program(EMBER_CLANGXX NAMES clang++ clang++-19 clang++-18 clang++-17 clang++-16 clang++-15 clang++-14)
    if(EMBER_CLANGXX)
      set(_probe ${CMAKE_BINARY_DIR}/CMakeFiles/ember_fuzz_probe)
      file(WRITE ${_probe}.cpp "extern \"C\" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n")
      execute_process(COMMAND ${EMBER_CLANGXX} -fsanitize=fuzzer,address,undefined ${_probe}.cpp -o ${_probe}
                      RESULT_VARIABLE _probe_rc OUTPUT_QUIET ERROR_QUIET)
      if(_probe_rc EQUAL 0)
        set(_ember_fuzz_sub ON)
      endif()
    endif()
  endif()
  if(NOT _ember_fuzz_sub)
    add_test(NAME fuzz.libfuzzer COMMAND sh -c
             "echo 'skipped: libFuzzer smoke runs need clang++ with libFuzzer (or -DEMBER_FUZZ=ON with clang++)'; exit 77")
    set_tests_properties(fuzz.libfuzzer PROPERTIES SKIP_RETURN_CODE 77)
    return()
  endif()
  include(ExternalProject)
  set(_targets)
  foreach(fmt ${_ember_fuzz_formats})
    list(APPEND _targets --target ember_fuzz_${fmt})
  endforeach()
  ExternalProject_Add(ember_fuzz_clang
    SOURCE_DIR ${CMAKE_SOURCE_DIR}
    BINARY_DIR ${CMAKE_BINARY_DIR}/fuzz
    CMAKE_ARGS -DCMAKE_CXX_COMPILER=${EMBER_CLANGXX} -DCMAKE_BUILD_TYPE=RelWithDebInfo -DEMBER_FUZZ=ON
               -DEMBER_BUILD_PYTHON=OFF -DEMBER_BUILD_BENCH=OFF -DEMBER_FUZZ_AUTO=OFF
    BUILD_COMMAND ${CMAKE_COMMAND} --build <BINARY_DIR> ${_targets}
    INSTALL_COMMAND ""
    BUILD_ALWAYS ON
    EXCLUDE_FROM_ALL OFF)
  foreach(fmt ${_ember_fuzz_formats})
    add_test(NAME fuzz.${fmt}.smoke
             COMMAND ${CMAKE_SOURCE_DIR}/tests/fuzz/run.sh ${CMAKE_BINARY_DIR}/fuzz/bin/ember_fuzz_${fmt} ${fmt} 2
                     ${CMAKE_BINARY_DIR}/fuzz-smoke/${fmt} ${_ember_fuzz_seeds})
    set_tests_properties(fuzz.${fmt}.smoke PROPERTIES TIMEOUT 120)
  endforeach()
  return()
endif()
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "EMBER_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
endif()
# The readers, instrumented for coverage and the sanitizers; the targets link
# them instead of ember_io.
set(_ember_fuzz_flags -fsanitize=address,undefined -fno-omit-frame-pointer -g)
file(GLOB _ember_io_sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/io/*.cpp)
add_library(ember_io_fuzz STATIC ${_ember_io_sources})
target_include_directories(ember_io_fuzz PUBLIC ${CMAKE_SOURCE_DIR}/include PRIVATE ${CMAKE_SOURCE_DIR}/src)
target_compile_options(ember_io_fuzz PRIVATE ${_ember_fuzz_flags} -fsanitize=fuzzer-no-link)
target_link_libraries(ember_io_fuzz PRIVATE lib3mf::lib3mf ZLIB::ZLIB TinyGLTF::TinyGLTF)
foreach(fmt ${_ember_fuzz_formats})
  add_executable(ember_fuzz_${fmt} ${CMAKE_SOURCE_DIR}/tests/fuzz/fuzz_${fmt}.cpp)
  target_include_directories(ember_fuzz_${fmt} PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_compile_options(ember_fuzz_${fmt} PRIVATE ${_ember_fuzz_flags} -fsanitize=fuzzer)
  target_link_options(ember_fuzz_${fmt} PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_libraries(ember_fuzz_${fmt} PRIVATE ember_io_fuzz lib3mf::lib3mf TinyGLTF::TinyGLTF)
  add_test(NAME fuzz.${fmt}.smoke
           COMMAND ${CMAKE_SOURCE_DIR}/tests/fuzz/run.sh $<TARGET_FILE:ember_fuzz_${fmt}> ${fmt} 2
                   ${CMAKE_BINARY_DIR}/fuzz-smoke/${fmt} ${_ember_fuzz_seeds})
  set_tests_properties(fuzz.${fmt}.smoke PROPERTIES TIMEOUT 120)
endforeach()
