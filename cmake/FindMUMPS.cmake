# FindMUMPS: parallel MUMPS 5 (Debian: libmumps-dev), double and single
# precision. Defines MUMPS::MUMPS (dmumps + smumps + mumps_common + pord).
find_path(MUMPS_INCLUDE_DIR dmumps_c.h)
find_library(MUMPS_DMUMPS_LIBRARY dmumps)
find_library(MUMPS_SMUMPS_LIBRARY smumps)
find_library(MUMPS_COMMON_LIBRARY mumps_common)
find_library(MUMPS_PORD_LIBRARY pord)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MUMPS
  REQUIRED_VARS MUMPS_DMUMPS_LIBRARY MUMPS_SMUMPS_LIBRARY MUMPS_COMMON_LIBRARY MUMPS_INCLUDE_DIR)
if(MUMPS_FOUND AND NOT TARGET MUMPS::MUMPS)
  add_library(MUMPS::MUMPS INTERFACE IMPORTED)
  set(_libs ${MUMPS_DMUMPS_LIBRARY} ${MUMPS_SMUMPS_LIBRARY} ${MUMPS_COMMON_LIBRARY})
  if(MUMPS_PORD_LIBRARY)
    list(APPEND _libs ${MUMPS_PORD_LIBRARY})
  endif()
  set_target_properties(MUMPS::MUMPS PROPERTIES
    INTERFACE_LINK_LIBRARIES "${_libs}"
    INTERFACE_INCLUDE_DIRECTORIES "${MUMPS_INCLUDE_DIR}")
endif()
mark_as_advanced(MUMPS_INCLUDE_DIR MUMPS_DMUMPS_LIBRARY MUMPS_SMUMPS_LIBRARY MUMPS_COMMON_LIBRARY MUMPS_PORD_LIBRARY)
