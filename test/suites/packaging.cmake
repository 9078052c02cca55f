# Packaging and launching: the package arrows of doc/architecture.md, an
# install consumed by a host code, MPMD launches of ddcontact.

# Every rank uses rank 0's command line and deck: an MPMD launch with other
# arguments on rank 1 runs rank 0's deck or fails on every rank, never hangs;
# files named in the deck (Gmsh, element map) must be the same on every rank
# (per-rank working directories stand in for rank-local file systems).
# (An MPMD launch with another program: the negative cases mpmd_ddcontact_*.)
add_test(NAME mpmd_rank0_command_line COMMAND ${CMAKE_COMMAND}
  -DMPIEXEC=${DDC_MPIEXEC} -DAPP=${DDC_APP} -DINPUTS=${DDC_INPUTS}
  -DMESHES=${PROJECT_SOURCE_DIR}/packages/io/test/data -DWORK_DIR=${DDC_RUNS}/mpmd
  -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/RunMpmd.cmake)
set_tests_properties(mpmd_rank0_command_line PROPERTIES ENVIRONMENT "${DDC_TEST_ENVIRONMENT}" PROCESSORS 2
  TIMEOUT ${DDC_TEST_TIMEOUT} LABELS "system;negative")

# Package arrows (doc/architecture.md): a package sees only the headers
# of the packages it depends on.
# Each probe is one translation unit of package <p> that includes one header;
# the allowed ones must compile, the forbidden ones must fail for want of the
# header. Built by the test (EXCLUDE_FROM_ALL), not by the default build.
set(_arrow_allowed)
set(_arrow_forbidden)
foreach(probe
    "core:DDC_Mesh.hpp:allowed" "io:DDC_Mesh.hpp:allowed" "contact:DDC_Element.hpp:allowed"
    "model:DDC_ContactComponent.hpp:allowed" "model:DDC_FetiDpSolver.hpp:allowed"
    "steps:DDC_Model.hpp:allowed" "analysis:DDC_StepController.hpp:allowed" "analysis:DDC_VtkWriter.hpp:allowed"
    "core:DDC_VtkWriter.hpp:forbidden" "core:DDC_Element.hpp:forbidden" "io:DDC_Model.hpp:forbidden"
    "elements:DDC_ContactComponent.hpp:forbidden" "contact:DDC_FetiDpSolver.hpp:forbidden"
    "feti:DDC_ContactComponent.hpp:forbidden" "model:DDC_OutputDirectory.hpp:forbidden"
    "model:DDC_StepController.hpp:forbidden" "steps:DDC_HistoryWriter.hpp:forbidden"
    "steps:DDC_Analysis.hpp:forbidden")
  string(REPLACE ":" ";" parts "${probe}")
  list(GET parts 0 package)
  list(GET parts 1 header)
  list(GET parts 2 verdict)
  string(REGEX REPLACE "[.]hpp$" "" stem "${header}")
  set(target arrow_probe_${package}_${stem})
  add_library(${target} OBJECT EXCLUDE_FROM_ALL ${CMAKE_CURRENT_SOURCE_DIR}/support/DDC_PackageArrowProbe.cpp)
  target_compile_definitions(${target} PRIVATE "DDC_PROBE_HEADER=\"${header}\"")
  target_link_libraries(${target} PRIVATE ddcontact_${package})
  if(verdict STREQUAL "allowed")
    list(APPEND _arrow_allowed ${target})
  else()
    list(APPEND _arrow_forbidden "${target}:${header}")
  endif()
endforeach()
string(REPLACE ";" "|" _arrow_allowed "${_arrow_allowed}")
string(REPLACE ";" "|" _arrow_forbidden "${_arrow_forbidden}")
add_test(NAME package_arrows COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
  "-DALLOWED=${_arrow_allowed}" "-DFORBIDDEN=${_arrow_forbidden}"
  -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/CheckPackageArrows.cmake)
# It builds in this build tree, as install_and_consume installs from it: the
# two never run at the same time (the lock), other tests may run beside them.
set_tests_properties(package_arrows PROPERTIES LABELS "unit;install" RESOURCE_LOCK build_tree
  TIMEOUT ${DDC_TEST_TIMEOUT})

# Host codes: install DDContact and consume it with find_package.
add_test(NAME install_and_consume COMMAND ${CMAKE_COMMAND}
  -DBUILD_DIR=${PROJECT_BINARY_DIR} -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/install_consume
  -DEXAMPLES_SUBDIR=${CMAKE_INSTALL_DATADIR}/ddcontact/examples/embedding
  "-DLAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER}"
  -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/InstallAndConsume.cmake)
set_tests_properties(install_and_consume PROPERTIES ENVIRONMENT "${DDC_TEST_ENVIRONMENT}" TIMEOUT ${DDC_TEST_TIMEOUT_LONG}
  LABELS "system;install" RESOURCE_LOCK build_tree PROCESSORS 2)
