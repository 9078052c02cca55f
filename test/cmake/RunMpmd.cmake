# MPMD launches of ddcontact: "mpirun -np 1 ddcontact A : -np 1 ddcontact B".
# Every rank runs rank 0's command line and deck (broadcast), so such a
# launch runs A or fails cleanly on both ranks; it used to hang (the ranks
# built different models and waited in different collectives). Files named
# in the deck must be the same on every rank: the ranks get different
# working directories here, as ranks on nodes without a shared file system
# see different files.
#   -DMPIEXEC=<mpirun> -DAPP=<ddcontact> -DINPUTS=<test/inputs>
#   -DMESHES=<packages/io/test/data> -DWORK_DIR=<scratch directory>
# Each launch must end within TIMEOUT seconds (a hang is a failure).
set(TIMEOUT 120)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# launch(<name> <expect: success|failure> REGEX <regex>... COMMAND <mpirun arguments>...):
# the output (stdout then stderr) must match every regex.
function(launch name expect)
  cmake_parse_arguments(L "" "" "REGEX;COMMAND" ${ARGN})
  execute_process(COMMAND ${MPIEXEC} --oversubscribe ${L_COMMAND} WORKING_DIRECTORY ${WORK_DIR}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT ${TIMEOUT})
  set(all "${out}${err}")
  message("---- ${name}: exit ${rc}\n${all}")
  if(NOT rc MATCHES "^[0-9]+$")
    message(FATAL_ERROR "${name}: did not end within ${TIMEOUT} s (${rc})")
  endif()
  if(expect STREQUAL "success" AND NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: expected success, got exit status ${rc}")
  elseif(expect STREQUAL "failure" AND rc EQUAL 0)
    message(FATAL_ERROR "${name}: expected a non-zero exit status, got 0")
  endif()
  foreach(regex IN LISTS L_REGEX)
    if(NOT all MATCHES "${regex}")
      message(FATAL_ERROR "${name}: output does not match: ${regex}")
    endif()
  endforeach()
  if(all MATCHES "MPI_ABORT was invoked")
    message(FATAL_ERROR "${name}: every rank must end cleanly, not through MPI_Abort")
  endif()
endfunction()

set(GOOD ${INPUTS}/small_block.xml)
set(BAD ${INPUTS}/negative/zero_steps.xml)

# 1. Rank 0's deck is valid, rank 1's is not: both ranks run rank 0's deck
#    into rank 0's output directory; rank 1's is never made.
launch(good_then_bad success
  REGEX "rank 1 was started with other arguments than rank 0. every rank runs rank 0's" "step +2/2"
  COMMAND -np 1 ${APP} ${GOOD} --output-dir a0 : -np 1 ${APP} ${BAD} --output-dir a1)
if(NOT EXISTS ${WORK_DIR}/a0/history.csv OR EXISTS ${WORK_DIR}/a1 OR EXISTS ${WORK_DIR}/a1.partial)
  message(FATAL_ERROR "good_then_bad: expected results in a0 only")
endif()
file(STRINGS ${WORK_DIR}/a0/history.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 3)
  message(FATAL_ERROR "good_then_bad: a0/history.csv has ${n} lines, expected a header and 2 steps")
endif()

# 2. Rank 0's deck is invalid: both ranks fail with rank 0's message.
launch(bad_then_good failure REGEX "Load Stepping/Number of Steps' must be > 0, got 0"
  COMMAND -np 1 ${APP} ${BAD} --output-dir b0 : -np 1 ${APP} ${GOOD} --output-dir b1)
if(EXISTS ${WORK_DIR}/b1/history.csv)
  message(FATAL_ERROR "bad_then_good: rank 1's deck was run")
endif()

# 3. A Gmsh file named in the deck that only rank 0 can read (relative to
#    the deck, which rank 0 reads from its working directory r0): every
#    rank fails naming the parameter, the file and the rank.
file(MAKE_DIRECTORY ${WORK_DIR}/r0 ${WORK_DIR}/r1)
file(READ ${INPUTS}/negative/gmsh_body.xml.in deck)
string(REPLACE "@MSH@" "body.msh" deck "${deck}")
string(REPLACE "@ELEMENT@" "Quad4" deck "${deck}")
file(WRITE ${WORK_DIR}/r0/deck.xml "${deck}")
configure_file(${MESHES}/rect2x1.msh ${WORK_DIR}/r0/body.msh COPYONLY)
launch(mesh_on_rank0_only failure
  REGEX "'Mesh/Bodies/Block/Gmsh/File' = '\\./body.msh': the file can be read on 1 of 2 ranks but not on rank 1"
  COMMAND -np 1 -wdir ${WORK_DIR}/r0 ${APP} deck.xml --output-dir ../c : -np 1 -wdir ${WORK_DIR}/r1 ${APP} deck.xml)

# 4. The same file name with other contents on rank 1.
configure_file(${MESHES}/two_surfaces.msh ${WORK_DIR}/r1/body.msh COPYONLY)
launch(mesh_differs failure REGEX "'Mesh/Bodies/Block/Gmsh/File' = '\\./body.msh': the file differs between ranks"
  COMMAND -np 1 -wdir ${WORK_DIR}/r0 ${APP} deck.xml --output-dir ../c : -np 1 -wdir ${WORK_DIR}/r1 ${APP} deck.xml)

# 5. The same file on both ranks passes the check; the run then fails later,
#    on both ranks alike (the template deck holds no boundary conditions).
configure_file(${MESHES}/rect2x1.msh ${WORK_DIR}/r1/body.msh COPYONLY)
launch(mesh_same failure REGEX "body 'Block' is not supported"
  COMMAND -np 1 -wdir ${WORK_DIR}/r0 ${APP} deck.xml --output-dir ../c : -np 1 -wdir ${WORK_DIR}/r1 ${APP} deck.xml)
