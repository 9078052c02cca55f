# FindPTScotch: PT-Scotch 7, the parallel graph partitioner, with 32-bit
# SCOTCH_Num (Debian: libptscotch-dev, headers under /usr/include/scotch).
# Defines PTScotch::PTScotch (libptscotch, libscotch and the error handlers
# that return error codes instead of exiting).
find_path(PTScotch_INCLUDE_DIR ptscotch.h PATH_SUFFIXES scotch)
find_library(PTScotch_LIBRARY ptscotch)
find_library(PTScotch_SCOTCH_LIBRARY scotch)
find_library(PTScotch_ERR_LIBRARY ptscotcherr)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(PTScotch
  REQUIRED_VARS PTScotch_LIBRARY PTScotch_SCOTCH_LIBRARY PTScotch_ERR_LIBRARY PTScotch_INCLUDE_DIR)
if(PTScotch_FOUND AND NOT TARGET PTScotch::PTScotch)
  add_library(PTScotch::PTScotch UNKNOWN IMPORTED)
  set_target_properties(PTScotch::PTScotch PROPERTIES
    IMPORTED_LOCATION "${PTScotch_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${PTScotch_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${PTScotch_SCOTCH_LIBRARY};${PTScotch_ERR_LIBRARY}")
endif()
mark_as_advanced(PTScotch_INCLUDE_DIR PTScotch_LIBRARY PTScotch_SCOTCH_LIBRARY PTScotch_ERR_LIBRARY)
