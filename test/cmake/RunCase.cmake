# Runs one ddcontact case for ctest and checks the outcome.
#   -DCMD=<|-list command>      the command (mpirun ... ddcontact deck args), '|'-separated
#   -DEXPECT=success|failure    required exit status class
#   -DREGEX=<regex>             must match stdout+stderr (optional)
#   -DALSO=<regex>              must match too (optional; the negative cases:
#                               the application's "ddcontact: error" prefix)
#   -DPRESERVE=<dir>            before: put an earlier DDContact result into <dir>
#                               (a copy of -DEARLIER=<dir>, a real result);
#                               after: every file of it must be byte-identical
#                               (SHA-256) and no file may have been added
#   -DSTATUS_DIR=<dir> -DRANKS=<n>  CMD runs each rank under
#                               tools/record_exit_status.sh <dir>: every rank
#                               must have left its exit status there, and
#                               each must match EXPECT (a rank killed by
#                               MPI_Abort, or hanging, leaves none)
#   -DABORT_EXPECTED=1          the failure may end the job through MPI_Abort
#                               (a rank runs another program that cannot end
#                               cleanly: the MPMD start-up handshake)
#   -DFILES=<|-list>            files that must exist afterwards and have been
#                               written by this run (not older than its start;
#                               optional)
string(REPLACE "|" ";" CMD "${CMD}")
string(REPLACE "|" ";" FILES "${FILES}")

# SHA-256 of every file below `dir`, as "relative-path=hash;..." in `out`.
function(ddc_tree_hashes dir out)
  file(GLOB_RECURSE entries LIST_DIRECTORIES false RELATIVE "${dir}" "${dir}/*")
  list(SORT entries)
  set(result)
  foreach(e ${entries})
    file(SHA256 "${dir}/${e}" h)
    list(APPEND result "${e}=${h}")
  endforeach()
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

if(PRESERVE)
  if(NOT EARLIER OR NOT EXISTS "${EARLIER}/ddcontact-result.txt")
    message(FATAL_ERROR "PRESERVE needs -DEARLIER=<a DDContact result directory>, got '${EARLIER}'")
  endif()
  file(REMOVE_RECURSE "${PRESERVE}" "${PRESERVE}.partial" "${PRESERVE}.old" "${PRESERVE}.lock")
  file(COPY "${EARLIER}/" DESTINATION "${PRESERVE}")
  ddc_tree_hashes("${PRESERVE}" before)
endif()
if(STATUS_DIR)
  file(REMOVE_RECURSE "${STATUS_DIR}")
  file(MAKE_DIRECTORY "${STATUS_DIR}")
endif()
# Files of an earlier run are left alone (removing a result's manifest would
# make it a directory DDContact refuses to replace); freshness is checked
# against this marker instead.
if(FILES)
  string(MD5 marker_name "${CMD}")
  set(marker "${CMAKE_CURRENT_BINARY_DIR}/run-case-${marker_name}.start")
  # (CMake compares modification times at the file system's resolution,
  # nanoseconds on Linux.)
  file(TOUCH "${marker}")
endif()
execute_process(COMMAND ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(all "${out}${err}")
message("${all}")
if(STATUS_DIR)
  # The wrapper makes every rank exit 0 towards mpirun (so that mpirun does
  # not kill the other ranks before they record theirs); the recorded
  # statuses are the ones that count.
  math(EXPR last "${RANKS} - 1")
  foreach(r RANGE 0 ${last})
    if(NOT EXISTS "${STATUS_DIR}/rank-${r}.status")
      message(FATAL_ERROR "rank ${r} left no exit status (killed, aborted or hung; mpirun exit ${rc})")
    endif()
    file(READ "${STATUS_DIR}/rank-${r}.status" s)
    string(STRIP "${s}" s)
    if(EXPECT STREQUAL "failure" AND s EQUAL 0)
      message(FATAL_ERROR "rank ${r} exited with status 0; every rank must report the failure")
    elseif(EXPECT STREQUAL "success" AND NOT s EQUAL 0)
      message(FATAL_ERROR "rank ${r} exited with status ${s}, expected 0")
    endif()
  endforeach()
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mpirun exited with status ${rc} although every rank recorded its own status")
  endif()
elseif(EXPECT STREQUAL "failure")
  if(rc EQUAL 0)
    message(FATAL_ERROR "expected a non-zero exit status, got 0")
  endif()
elseif(NOT rc EQUAL 0)
  message(FATAL_ERROR "expected success, got exit status ${rc}")
endif()
if(DEFINED REGEX AND NOT all MATCHES "${REGEX}")
  message(FATAL_ERROR "output does not match the expected message: ${REGEX}")
endif()
if(ALSO AND NOT all MATCHES "${ALSO}")
  message(FATAL_ERROR "output does not match: ${ALSO}")
endif()
if(EXPECT STREQUAL "failure" AND all MATCHES "MPI_ABORT was invoked" AND NOT ABORT_EXPECTED)
  message(FATAL_ERROR "an input error must end every rank cleanly, not through MPI_Abort")
endif()
if(PRESERVE)
  ddc_tree_hashes("${PRESERVE}" after)
  if(NOT before STREQUAL after)
    message(FATAL_ERROR "the earlier result in ${PRESERVE} changed:\n before: ${before}\n after:  ${after}")
  endif()
endif()
foreach(f ${FILES})
  if(NOT EXISTS "${f}")
    message(FATAL_ERROR "expected output file ${f} is missing")
  endif()
  if("${marker}" IS_NEWER_THAN "${f}" AND NOT "${f}" IS_NEWER_THAN "${marker}")
    message(FATAL_ERROR "expected output file ${f} was not written by this run (older than its start)")
  endif()
endforeach()
