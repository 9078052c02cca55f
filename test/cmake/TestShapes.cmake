# The shapes of the system tests, one function each (included by
# test/CMakeLists.txt; the -P scripts beside this file run at test time).
#
#   ddc_add_run_test        one ddcontact run under mpirun, checked by RunCase.cmake
#   ddc_add_tool_test       one run of a post-processing tool
#   ddc_add_script_test     a bash script of several runs (studies, fault injection)
#   ddc_check_history       values in the history.csv of a run
#   ddc_compare_histories   two runs' history.csv, column by column (compare_history)
#   ddc_mesh_mode           the arguments of a run with the whole mesh or the mesh in ranges
#   ddc_add_mpmd_startup_test  an MPMD launch with another program (the start-up handshake)
# The negative cases have their own table and function (NegativeCases.cmake).
#
# Runs that other tests read are ctest fixtures named after the run
# (ddc_add_run_test(... FIXTURE)): a test that reads run R requires the
# fixture R, so R runs first, once, and its readers are skipped if it fails.

# ddc_add_run_test(<name> RANKS <np> ARGS ... [FAIL] [PRESERVE] [FIXTURE] [FILES f...]
#                  [LABELS l...] [LAUNCHER cmd...] [ALSO r] [REGEX r])
# Every rank runs under tools/record_exit_status.sh: each rank's exit status
# is checked (all 0, or with FAIL all non-zero).
# PRESERVE: runs with --output-dir into a directory holding an earlier result
# and checks that the run leaves it byte-identical.
# FIXTURE: the run is the fixture <name> (other tests read its results).
# ALSO: a second regex the output must match.
# REGEX comes last: a regex with an unmatched '[' swallows the arguments after it.
function(ddc_add_run_test name)
  cmake_parse_arguments(R "FAIL;PRESERVE;FIXTURE" "RANKS;REGEX;ALSO" "ARGS;FILES;LABELS;LAUNCHER" ${ARGN})
  list(PREPEND R_LABELS system)
  if(NOT R_RANKS)
    set(R_RANKS 2)
  endif()
  set(args ${R_ARGS})
  set(extra)
  if(R_ALSO)
    list(APPEND extra "-DALSO=${R_ALSO}")
  endif()
  if(R_PRESERVE)
    set(dir ${DDC_RUNS}/${name})
    list(APPEND args --output-dir ${dir})
    list(APPEND extra -DPRESERVE=${dir} -DEARLIER=${DDC_EARLIER_RESULT})
  endif()
  ddc_mpi_command(cmd ${R_RANKS} sh ${CMAKE_CURRENT_SOURCE_DIR}/tools/record_exit_status.sh ${DDC_STATUS}/${name}
    ${DDC_APP} ${args})
  set(cmd ${R_LAUNCHER} ${cmd})  # e.g. prlimit --as=... (inherited by mpirun's ranks)
  # Lists travel to the script joined by '|' (a ';' would split the -D value).
  string(REPLACE ";" "|" cmd_escaped "${cmd}")
  string(REPLACE ";" "|" files_escaped "${R_FILES}")
  set(expect success)
  if(R_FAIL)
    set(expect failure)
  endif()
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DCMD=${cmd_escaped}" -DEXPECT=${expect}
    "-DREGEX=${R_REGEX}" "-DFILES=${files_escaped}" -DSTATUS_DIR=${DDC_STATUS}/${name} -DRANKS=${R_RANKS}
    ${extra} -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/RunCase.cmake)
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "${DDC_TEST_ENVIRONMENT}" PROCESSORS ${R_RANKS}
    TIMEOUT ${DDC_TEST_TIMEOUT} LABELS "${R_LABELS}")
  if(R_PRESERVE)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED earlier_result)
  endif()
  if(R_FIXTURE)
    set_tests_properties(${name} PROPERTIES FIXTURES_SETUP ${name})
  endif()
endfunction()

# ddc_add_tool_test(<name> TOOL <target> EXPECT success|failure [LABELS l...]
#                   ARGS <args>... REGEX <regex>): one run of a post-processing
# tool (ddcontact-figure4, ddcontact-hertz) checked by cmake/RunCase.cmake.
function(ddc_add_tool_test name)
  cmake_parse_arguments(T "" "TOOL;EXPECT;REGEX" "LABELS;ARGS" ${ARGN})
  list(PREPEND T_LABELS system)
  string(REPLACE ";" "|" cmd "$<TARGET_FILE:${T_TOOL}>;${T_ARGS}")
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DCMD=${cmd}" -DEXPECT=${T_EXPECT} "-DREGEX=${T_REGEX}"
    -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/RunCase.cmake)
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "${DDC_TEST_ENVIRONMENT}" LABELS "${T_LABELS}")
endfunction()

# ddc_add_script_test(<name> PROCESSORS <n> LABELS l... [LONG] [ENVIRONMENT e...]
#                     [FIXTURES f...] [PROPERTIES p v...] COMMAND <bash script> <args>...):
# a bash script that runs ddcontact several times (it fails on a non-zero
# exit status, or as PROPERTIES say). PROCESSORS: the most ranks it runs at
# once, at most 2 (the suite runs on 2 cores: a test that runs more ranks
# than it declares slows down the tests run beside it). LONG: the long time
# limit. FIXTURES: the runs it reads.
function(ddc_add_script_test name)
  cmake_parse_arguments(S "LONG" "PROCESSORS" "LABELS;ENVIRONMENT;FIXTURES;PROPERTIES;COMMAND" ${ARGN})
  list(PREPEND S_LABELS system)
  set(timeout ${DDC_TEST_TIMEOUT})
  set(environment ${DDC_TEST_ENVIRONMENT} ${S_ENVIRONMENT})
  if(S_LONG)
    set(timeout ${DDC_TEST_TIMEOUT_LONG})
  endif()
  add_test(NAME ${name} COMMAND bash ${S_COMMAND})
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "${environment}"
    PROCESSORS ${S_PROCESSORS} TIMEOUT ${timeout} LABELS "${S_LABELS}" ${S_PROPERTIES})
  if(S_FIXTURES)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "${S_FIXTURES}")
  endif()
endfunction()

# ddc_check_history(<name> <run> [NROWS n] CHECKS c... [LABELS l...]):
# values in the history.csv of run <run> (a run declared with FIXTURE; a
# path below ${DDC_RUNS} in a script's run directory with FIXTURE_OF <f>),
# checked by cmake/CheckHistory.cmake (ROWS:COLUMN:OP:VALUE[:VALUE2]).
function(ddc_check_history name run)
  cmake_parse_arguments(C "" "NROWS;FIXTURE_OF" "CHECKS;LABELS" ${ARGN})
  list(PREPEND C_LABELS system)
  string(REPLACE ";" "|" checks "${C_CHECKS}")
  set(extra)
  if(C_NROWS)
    set(extra -DNROWS=${C_NROWS})
  endif()
  set(fixture ${run})
  if(C_FIXTURE_OF)
    set(fixture ${C_FIXTURE_OF})
  endif()
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} -DHISTORY=${DDC_RUNS}/${run}/history.csv ${extra}
    "-DCHECKS=${checks}" -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/CheckHistory.cmake)
  set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED ${fixture} LABELS "${C_LABELS}")
endfunction()

# ddc_compare_histories(<name> <run a> <run b> <tolerance> [FILE f] [COLUMNS c...] [LABELS l...]):
# tools/compare_history.cpp on the history.csv (or the CSV file FILE) of two
# runs (both declared with FIXTURE): the COLUMNS (default: every column but
# wall_seconds) agree to <tolerance> relative ("exact": field for field).
function(ddc_compare_histories name a b tolerance)
  cmake_parse_arguments(C "" "FILE" "COLUMNS;LABELS" ${ARGN})
  list(PREPEND C_LABELS system)
  if(NOT C_FILE)
    set(C_FILE history.csv)
  endif()
  add_test(NAME ${name} COMMAND compare_history ${DDC_RUNS}/${a}/${C_FILE} ${DDC_RUNS}/${b}/${C_FILE}
    ${tolerance} ${C_COLUMNS})
  set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "${a};${b}" LABELS "${C_LABELS}")
endfunction()

# ddc_mesh_mode(<mode> <args var> <said var>): a run with the whole mesh on
# every rank (<mode> whole) or with the mesh built in ranges (in_ranges:
# Partition/Mesh On Every Rank = false, with PT-Scotch): the arguments that
# choose it, and the regular expression of what its distribution line says
# (';' in a bracket expression: a bare one would end the REGEX argument).
macro(ddc_mesh_mode mode args said)
  set(${args})
  set(${said} "every rank holds the whole mesh")
  if("${mode}" STREQUAL in_ranges)
    set(${args} --set "Partition/Mesh On Every Rank=false")
    set(${said} "[;] no rank held the whole mesh \\(built in ranges of elements\\)")
  endif()
endmacro()

# ddc_add_mpmd_startup_test(<name> first|second [LABELS l...] ARGS <deck> ... REGEX <regex>):
# an MPMD launch, ddcontact (with ARGS and --output-dir) on one rank and a
# unit-test binary that runs no test (its MPI main still makes collective
# calls) on the other: ddcontact first (rank 0) or second (rank 1). The job
# must end with the message; through MPI_Abort, as the other program cannot
# end cleanly (DDCONTACT_STARTUP_TIMEOUT in the case's environment).
function(ddc_add_mpmd_startup_test name side)
  cmake_parse_arguments(M "" "REGEX" "LABELS;ARGS" ${ARGN})
  list(PREPEND M_LABELS system)
  set(other $<TARGET_FILE:model_rigid_motion_check> --gtest_filter=-*)
  set(ddc ${DDC_APP} ${M_ARGS} --output-dir ${DDC_RUNS}/${name})
  if(side STREQUAL "first")
    ddc_mpi_command(cmd 1 ${ddc} : -np 1 ${other})
  else()
    ddc_mpi_command(cmd 1 ${other} : -np 1 ${ddc})
  endif()
  string(REPLACE ";" "|" cmd "${cmd}")
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DCMD=${cmd}" -DEXPECT=failure "-DREGEX=${M_REGEX}"
    "-DALSO=ddcontact: error" -DABORT_EXPECTED=1 -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/RunCase.cmake)
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "${DDC_TEST_ENVIRONMENT}" PROCESSORS 2 TIMEOUT 60
    LABELS "${M_LABELS}")
endfunction()
