# Tests that are scripts. The examples in docs/ are code the tests run, so the pages cannot drift from
# the interfaces they describe: the C++ API page's program is built and run
# here (and again as a find_package consumer, EmberInstall.cmake), the CLI
# page's commands run as one shell script; the Python page's example is run in
# EmberPython.cmake.
add_executable(ember_example_cpp ${CMAKE_SOURCE_DIR}/docs/examples/cpp_api.cpp)
target_link_libraries(ember_example_cpp PRIVATE ember ember_warnings)

if(EMBER_BUILD_TESTS)
  add_test(NAME docs.cpp_api_example COMMAND ember_example_cpp ${CMAKE_BINARY_DIR})
  add_test(NAME docs.cli_examples
           COMMAND bash ${CMAKE_SOURCE_DIR}/docs/examples/cli_examples.sh $<TARGET_FILE:ember_cli>
                   ${CMAKE_BINARY_DIR}/docs-cli-examples)
  set_tests_properties(docs.cpp_api_example docs.cli_examples PROPERTIES TIMEOUT 600)
endif()

# CLI behaviour a GoogleTest cannot see: the progress bar needs a terminal
# (a pseudo-terminal from Python's standard library).
if(EMBER_BUILD_TESTS)
  find_package(Python3 COMPONENTS Interpreter QUIET)
  if(Python3_Interpreter_FOUND)
    add_test(NAME cli.progress_tty
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/tests/cli/progress_tty.py $<TARGET_FILE:ember_cli>
                     ${CMAKE_BINARY_DIR}/cli-progress-tty)
    set_tests_properties(cli.progress_tty PROPERTIES TIMEOUT 300)
  endif()
endif()

# The include structure (tools/check_includes.py): no include cycles, every
# source starts with its own header, installed headers include nothing from src/.
if(EMBER_BUILD_TESTS)
  find_package(Python3 COMPONENTS Interpreter QUIET)
  if(Python3_Interpreter_FOUND)
    add_test(NAME layout.include_structure COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/tools/check_includes.py
                                                   ${CMAKE_SOURCE_DIR})
  endif()
endif()
