# The negative cases (test/negative_cases.txt; its header says the format),
# declared by one function. What a case proves: the bad input (a deck, --set
# options, a command line, an environment) ends the run with a message that
# names the cause, a non-zero exit status on every rank (each rank's status
# recorded by tools/record_exit_status.sh, none ended by MPI_Abort), and an
# earlier result in the output directory left byte-identical (PRESERVE).
#
# Where a case is checked ("via", by default from its stage):
#   in-process  the cases that fail before the model is built (stage deck or
#               validation): packages/analysis/test/DDC_NegativeCasesTest.cpp
#               reads the table and checks each in one process per rank
#               count (ctests analysis_negative_cases_np1/np2 and, for cases
#               that need files other tests make, negative_run_outputs_np1/np2
#               declared here);
#   app         everything else (the command line, the start-up, the model
#               build, a run, a special launcher, MPMD, the post-processing
#               tools) and a representative case of each stage checked in
#               process: one ctest per rank count, negative_<case> (one rank
#               count) or negative_<case>_np<r>, which also requires the
#               application's prefix "ddcontact: error" (the message the
#               in-process check sees is what follows it).
# Every one is labelled `negative`.

# ddc_negative_placeholders(<var>): `var` with the table's directory
# placeholders replaced.
macro(ddc_negative_placeholders var)
  string(REPLACE "@NEGATIVE@" "${DDC_INPUTS}/negative" ${var} "${${var}}")
  string(REPLACE "@INPUTS@" "${DDC_INPUTS}" ${var} "${${var}}")
  string(REPLACE "@EXAMPLES@" "${PROJECT_SOURCE_DIR}/examples" ${var} "${${var}}")
  string(REPLACE "@SOURCE@" "${PROJECT_SOURCE_DIR}" ${var} "${${var}}")
  string(REPLACE "@DECKS@" "${DDC_DECKS}" ${var} "${${var}}")
  string(REPLACE "@RUNS@" "${DDC_RUNS}" ${var} "${${var}}")
endmacro()

# ddc_declare_negative_case(): the case held in the C_* variables of the
# caller (ddc_add_negative_cases), declared as its application runs. A
# regex may hold an unmatched '[' (e.g. "must lie in \[0, 1\)"), which
# would swallow the list elements after it: it is always the last argument.
function(ddc_declare_negative_case)
  if(NOT C_case OR NOT C_stage OR NOT C_ranks OR "${C_regex}" STREQUAL "")
    message(FATAL_ERROR "${DDC_NEGATIVE_TABLE}: case '${C_case}' needs a stage, ranks and a regex")
  endif()
  set(via ${C_via})
  if(NOT via)
    if(C_stage STREQUAL "deck" OR C_stage STREQUAL "validation")
      set(via in-process)
    else()
      set(via app)
    endif()
  endif()
  if("in-process" IN_LIST via AND C_fixture)
    set_property(GLOBAL APPEND PROPERTY DDC_NEGATIVE_RUN_OUTPUT_FIXTURES ${C_fixture})
  endif()
  if(NOT "app" IN_LIST via)
    return()
  endif()
  set(args)
  if(C_deck)
    list(APPEND args ${C_deck})
  endif()
  foreach(s IN LISTS C_set)
    list(APPEND args --set "${s}")
  endforeach()
  list(APPEND args ${C_arg})
  list(LENGTH C_ranks nranks)
  set(labels negative ${C_labels})
  if(C_stage STREQUAL "tool")
    ddc_add_tool_test(negative_${C_case} TOOL ${C_app} EXPECT failure LABELS ${labels} ARGS ${args} REGEX "${C_regex}")
    set(names negative_${C_case})
  elseif(C_mpmd)
    ddc_add_mpmd_startup_test(negative_${C_case} ${C_mpmd} LABELS ${labels} ARGS ${args} REGEX "${C_regex}")
    set(names negative_${C_case})
  else()
    set(names)
    foreach(np IN LISTS C_ranks)
      set(name negative_${C_case})
      if(nranks GREATER 1)
        set(name negative_${C_case}_np${np})
      endif()
      ddc_add_run_test(${name} FAIL PRESERVE RANKS ${np} LAUNCHER ${C_launcher} LABELS ${labels} ARGS ${args}
        ALSO "ddcontact: error" REGEX "${C_regex}")
      list(APPEND names ${name})
    endforeach()
  endif()
  foreach(name IN LISTS names)
    if(C_fixture)
      set_property(TEST ${name} APPEND PROPERTY FIXTURES_REQUIRED ${C_fixture})
    endif()
    if(C_env)
      set_property(TEST ${name} APPEND PROPERTY ENVIRONMENT ${C_env})
    endif()
  endforeach()
endfunction()

# ddc_add_negative_cases(<table>): every case of the table. A line is
# "<key> <value>"; "case" starts a case; '#' lines are comments.
function(ddc_add_negative_cases table)
  set(DDC_NEGATIVE_TABLE ${table})
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${table})
  # file(STRINGS) escapes a ';' in a line ("\;"); square brackets would
  # group list elements, so they are hidden while the lines are split.
  file(STRINGS ${table} lines ENCODING UTF-8)
  string(REPLACE "[" "<ddc-lb>" lines "${lines}")
  string(REPLACE "]" "<ddc-rb>" lines "${lines}")
  set(keys case stage ranks via deck set arg regex fixture labels launcher env app mpmd)
  set(C_case)
  foreach(line IN LISTS lines)
    if(line MATCHES "^[ \t]*(#|$)")
      continue()
    endif()
    if(NOT line MATCHES "^([a-z-]+)[ \t]*(.*)$")
      message(FATAL_ERROR "${table}: cannot read the line '${line}'")
    endif()
    set(key ${CMAKE_MATCH_1})
    string(STRIP "${CMAKE_MATCH_2}" value)
    string(REPLACE "<ddc-lb>" "[" value "${value}")
    string(REPLACE "<ddc-rb>" "]" value "${value}")
    if(NOT key IN_LIST keys)
      message(FATAL_ERROR "${table}: unknown key '${key}' in case '${C_case}'")
    endif()
    if(key STREQUAL "case")
      if(C_case)
        ddc_declare_negative_case()
      endif()
      foreach(k IN LISTS keys)
        set(C_${k})
      endforeach()
    endif()
    ddc_negative_placeholders(value)
    if(key MATCHES "^(ranks|via|fixture|labels|launcher)$")
      separate_arguments(value UNIX_COMMAND "${value}")
      list(APPEND C_${key} ${value})
    elseif(key MATCHES "^(set|arg|env)$")
      if(value MATCHES "[][;]")
        message(FATAL_ERROR "${table}: case '${C_case}': no '[', ']' or ';' in a ${key} line (CMake lists)")
      endif()
      list(APPEND C_${key} "${value}")
    else()
      set(C_${key} "${value}")
    endif()
  endforeach()
  if(C_case)
    ddc_declare_negative_case()
  endif()
  # The in-process cases that need files other tests make.
  get_property(fixtures GLOBAL PROPERTY DDC_NEGATIVE_RUN_OUTPUT_FIXTURES)
  if(fixtures)
    list(REMOVE_DUPLICATES fixtures)
    ddc_register_unit_test(analysis_negative_cases negative_run_outputs RANKS 1 2 LABELS system negative
      ARGS "--gtest_filter=RunOutputs/*")
    foreach(np 1 2)
      set_property(TEST negative_run_outputs_np${np} APPEND PROPERTY FIXTURES_REQUIRED ${fixtures})
    endforeach()
  endif()
endfunction()
