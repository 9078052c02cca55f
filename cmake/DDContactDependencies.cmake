# Finds every dependency of DDContact and stops with a readable message that
# names the Debian package to install when one is missing.

function(ddc_missing what debpkg)
  message(FATAL_ERROR
    "DDContact: ${what} was not found.\n"
    "  Install it with:  apt-get install -y ${debpkg}\n"
    "  (or run cmake/setup.sh, which installs every dependency).")
endfunction()

find_package(MPI COMPONENTS C CXX)
if(NOT MPI_FOUND)
  ddc_missing("MPI (Open MPI)" "libopenmpi-dev openmpi-bin")
endif()

# Trilinos 13.2: the packages DDContact uses. Debian's TrilinosConfig.cmake
# also needs libptscotch-dev to be installed to load at all.
set(DDC_TRILINOS_PACKAGES Teuchos Tpetra Amesos2 Belos MueLu ShyLU_DDFROSch Xpetra Zoltan2)
find_package(Trilinos 13.2 QUIET COMPONENTS ${DDC_TRILINOS_PACKAGES})
if(NOT Trilinos_FOUND)
  ddc_missing("Trilinos >= 13.2 with ${DDC_TRILINOS_PACKAGES}" "trilinos-all-dev libptscotch-dev")
endif()
message(STATUS "DDContact: Trilinos ${Trilinos_VERSION} at ${Trilinos_DIR}")

find_package(METIS)
if(NOT METIS_FOUND)
  ddc_missing("METIS 5" "libmetis-dev")
endif()
find_package(PTScotch)
if(NOT PTScotch_FOUND)
  ddc_missing("PT-Scotch 7 (parallel graph partitioning)" "libptscotch-dev")
endif()
find_package(MUMPS)
if(NOT MUMPS_FOUND)
  ddc_missing("MUMPS (double precision, MPI)" "libmumps-dev")
endif()
find_package(CHOLMOD)
if(NOT CHOLMOD_FOUND)
  ddc_missing("CHOLMOD (SuiteSparse)" "libsuitesparse-dev")
endif()
find_package(ExodusII)
if(NOT ExodusII_FOUND)
  ddc_missing("Exodus II" "libexodusii-dev")
endif()
find_package(Eigen3 3.3 NO_MODULE QUIET)
if(NOT TARGET Eigen3::Eigen)
  ddc_missing("Eigen 3" "libeigen3-dev")
endif()

# One interface target carrying Trilinos (package libraries only, not the
# whole TPL list) plus MPI, so the package libraries stay short to declare.
if(NOT TARGET DDContact_Trilinos)
  add_library(DDContact_Trilinos INTERFACE)
  target_include_directories(DDContact_Trilinos SYSTEM INTERFACE ${Trilinos_INCLUDE_DIRS})
  # Zoltan2 headers (pulled in by MueLu) include ptscotch.h, which Debian
  # installs under /usr/include/scotch.
  find_path(DDC_PTSCOTCH_INCLUDE_DIR ptscotch.h PATH_SUFFIXES scotch)
  if(NOT DDC_PTSCOTCH_INCLUDE_DIR)
    ddc_missing("PT-Scotch headers (ptscotch.h)" "libptscotch-dev")
  endif()
  target_include_directories(DDContact_Trilinos SYSTEM INTERFACE ${DDC_PTSCOTCH_INCLUDE_DIR})
  target_link_libraries(DDContact_Trilinos INTERFACE ${Trilinos_LIBRARIES} MPI::MPI_CXX)
  if(DDContact_ENABLE_SANITIZERS)
    # Instrumented DDContact libraries need the sanitizer runtimes in every
    # program that links them, host codes included.
    target_link_options(DDContact_Trilinos INTERFACE -fsanitize=address,undefined)
  endif()
  install(TARGETS DDContact_Trilinos EXPORT DDContactTargets)
endif()
