# Finds lib3mf 1.x (Debian lib3mf-dev) and defines the imported target
# lib3mf::lib3mf. lib3mf 1.x ships no CMake package, and its pkg-config file
# asks to link -lzip -lz, which needs libzip-dev although lib3MF.so already
# links libzip itself; so the header and the library are found directly.
# Installed with ember's package, whose emberConfig.cmake uses it too.
find_path(LIB3MF_INCLUDE_DIR Model/COM/NMR_DLLInterfaces.h PATH_SUFFIXES lib3mf)
find_library(LIB3MF_LIBRARY NAMES 3MF lib3MF)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(lib3mf REQUIRED_VARS LIB3MF_LIBRARY LIB3MF_INCLUDE_DIR)
if(lib3mf_FOUND AND NOT TARGET lib3mf::lib3mf)
  add_library(lib3mf::lib3mf UNKNOWN IMPORTED)
  set_target_properties(lib3mf::lib3mf PROPERTIES IMPORTED_LOCATION ${LIB3MF_LIBRARY}
                                                  INTERFACE_INCLUDE_DIRECTORIES ${LIB3MF_INCLUDE_DIR})
endif()
mark_as_advanced(LIB3MF_INCLUDE_DIR LIB3MF_LIBRARY)
