# FindCHOLMOD: SuiteSparse's CHOLMOD (Debian: libsuitesparse-dev), header in
# suitesparse/. Defines CHOLMOD::CHOLMOD (cholmod + suitesparseconfig; the
# rest of SuiteSparse, METIS, BLAS/LAPACK and the OpenMP runtime come with
# libcholmod's own dependencies). Not Trilinos' libtrilinos_trilinosss: its
# SuiteSparse pieces (AMD, KLU, ...) carry a trilinos_ prefix, so both link
# into one program.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(CHOLMOD_SUITESPARSECONFIG_LIBRARY suitesparseconfig)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_SUITESPARSECONFIG_LIBRARY CHOLMOD_INCLUDE_DIR)
if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  add_library(CHOLMOD::CHOLMOD INTERFACE IMPORTED)
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
    INTERFACE_LINK_LIBRARIES "${CHOLMOD_LIBRARY};${CHOLMOD_SUITESPARSECONFIG_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY CHOLMOD_SUITESPARSECONFIG_LIBRARY)
