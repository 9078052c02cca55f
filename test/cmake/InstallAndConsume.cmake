# Installs DDContact from BUILD_DIR into a temporary prefix, then configures,
# builds and runs the host programs installed with it (EXAMPLES_SUBDIR below
# the prefix: share/ddcontact/examples/embedding, doc/embedding.md) with
# find_package(DDContact) and nothing but the installed package.
#   -DBUILD_DIR=<build tree> -DWORK_DIR=<scratch> -DEXAMPLES_SUBDIR=<below the prefix>
#   [-DLAUNCHER=<compiler launcher>]
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
set(CONSUMER_SOURCE ${prefix}/${EXAMPLES_SUBDIR})
if(NOT EXISTS ${CONSUMER_SOURCE}/CMakeLists.txt)
  message(FATAL_ERROR "the install did not put the host examples in ${CONSUMER_SOURCE}")
endif()
# LAUNCHER: the compiler launcher of the DDContact build (ccache), if any:
# the host programs compile as they would without it, only faster again.
set(launcher)
if(LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release ${launcher})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build --parallel 2)
find_program(MPIRUN NAMES mpirun mpiexec REQUIRED)
run(${MPIRUN} --oversubscribe -np 2 ${WORK_DIR}/build/host_program)
# Depth (b) alone: the host's own linear system with FetiDpSolver against a
# direct solve, both subdomains on one rank and one per rank.
foreach(np 1 2)
  run(${MPIRUN} --oversubscribe -np ${np} ${WORK_DIR}/build/host_feti)
endforeach()
# Depths (b) and (c): the host's own mesh, element loop and Newton with the
# contact component and FetiDpSolver reproduce the whole analysis to 1e-10.
run(${MPIRUN} --oversubscribe -np 2 ${WORK_DIR}/build/host_contact_feti)
# Depth (c) in 3-D: the contact component alone on two Hex8 blocks, on 1, 2
# and 3 ranks.
foreach(np 1 2 3)
  run(${MPIRUN} --oversubscribe -np ${np} ${WORK_DIR}/build/host_contact_3d)
endforeach()
