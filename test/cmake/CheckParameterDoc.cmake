# doc/parameters.md must equal the output of `ddcontact --print-parameters`.
execute_process(COMMAND ${APP} --print-parameters RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ddcontact --print-parameters failed (${rc})")
endif()
file(READ ${DOC} doc)
if(NOT doc STREQUAL out)
  message(FATAL_ERROR "${DOC} is out of date: regenerate it with\n  build/src/ddcontact --print-parameters > doc/parameters.md")
endif()
