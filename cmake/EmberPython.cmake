# The Python module `ember` (pybind11 over numpy arrays), built into
# build/python so that PYTHONPATH=build/python imports it, and installed with
# `cmake --install` into EMBER_PYTHON_INSTALL_DIR.
#
# Debian's python3-pybind11 and python3-numpy belong to /usr/bin/python3; a
# python3 earlier on PATH (pyenv, a venv) usually has neither, so that
# interpreter is preferred unless Python3_EXECUTABLE is given.
if(NOT EMBER_BUILD_PYTHON)
  return()
endif()
if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module)
find_package(pybind11 CONFIG QUIET)
if(NOT Python3_FOUND OR NOT pybind11_FOUND)
  message(WARNING "ember: the Python module is skipped: pybind11 or the Python headers are missing "
                  "(scripts/setup.sh installs python3-dev, pybind11-dev, python3-pybind11, python3-numpy)")
  return()
endif()

file(GLOB EMBER_PYTHON_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/python/*.cpp)
pybind11_add_module(ember_python MODULE ${EMBER_PYTHON_SOURCES})
set_target_properties(ember_python PROPERTIES OUTPUT_NAME ember LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/python)
target_include_directories(ember_python PRIVATE ${CMAKE_SOURCE_DIR}/src)
target_link_libraries(ember_python PRIVATE ember ember_warnings)

# Default: the interpreter's own package path relative to the prefix. Debian's
# default scheme adds "local/" (it means prefix /usr); stripped, prefix
# /usr/local gives /usr/local/lib/python3.X/dist-packages, which Debian's
# python3 searches.
execute_process(COMMAND ${Python3_EXECUTABLE} -c
                        "import sysconfig; p = sysconfig.get_path('platlib', vars={'platbase': '', 'base': ''}).lstrip('/'); print(p[6:] if p.startswith('local/') else p)"
                OUTPUT_VARIABLE _ember_platlib OUTPUT_STRIP_TRAILING_WHITESPACE)
set(EMBER_PYTHON_INSTALL_DIR ${_ember_platlib} CACHE STRING "Where `cmake --install` puts the Python module (relative to the prefix)")
install(TARGETS ember_python LIBRARY DESTINATION ${EMBER_PYTHON_INSTALL_DIR})

if(EMBER_BUILD_TESTS)
  add_test(NAME python.module
           COMMAND ${Python3_EXECUTABLE} -m unittest discover -s ${CMAKE_SOURCE_DIR}/tests/python -p "test_*.py" -v)
  add_test(NAME docs.python_example
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/docs/examples/python_example.py ${CMAKE_BINARY_DIR}/docs-python-example)
  set_tests_properties(python.module docs.python_example PROPERTIES
                       ENVIRONMENT "PYTHONPATH=${CMAKE_BINARY_DIR}/python;EMBER_CLI=$<TARGET_FILE:ember_cli>"
                       TIMEOUT 600)
endif()
