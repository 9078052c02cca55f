# The command line (--help, --print-parameters), the generated parameter
# reference, and the earlier result the PRESERVE checks of the negative cases
# copy (a real result of a small run).
ddc_add_run_test(app_help RANKS 1 ARGS --help REGEX "usage: ddcontact INPUT.xml")
ddc_add_run_test(app_print_parameters RANKS 1 ARGS --print-parameters
  REGEX "Young.s Modulus.*Number of Steps")
# The parameter reference in doc/ is generated; it must match the program.
add_test(NAME doc_parameters_up_to_date COMMAND ${CMAKE_COMMAND}
  -DAPP=${DDC_APP} -DDOC=${PROJECT_SOURCE_DIR}/doc/parameters.md
  -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/CheckParameterDoc.cmake)
set_tests_properties(doc_parameters_up_to_date PROPERTIES ENVIRONMENT "${DDC_TEST_ENVIRONMENT}" LABELS system)

ddc_add_run_test(earlier_result RANKS 2 ARGS ${DDC_INPUTS}/small_block.xml --output-dir ${DDC_EARLIER_RESULT}
  FILES ${DDC_EARLIER_RESULT}/history.csv ${DDC_EARLIER_RESULT}/ddcontact-result.txt)
set_tests_properties(earlier_result PROPERTIES FIXTURES_SETUP earlier_result)
# --set overrides a parameter of the deck.
ddc_add_run_test(override_steps RANKS 2
  ARGS ${DDC_INPUTS}/small_block.xml --set "Load Stepping/Number of Steps=3" --output-dir ${DDC_RUNS}/override_steps
  REGEX "step +3/3")
# A UTF-8 byte-order mark is skipped (UTF-16 is refused: negative_cases.txt, deck_utf16).
ddc_add_run_test(deck_utf8_bom RANKS 2 ARGS ${DDC_INPUTS}/deck_utf8_bom.xml --output-dir ${DDC_RUNS}/deck_utf8_bom
  REGEX "results in" FILES ${DDC_RUNS}/deck_utf8_bom/history.csv)
