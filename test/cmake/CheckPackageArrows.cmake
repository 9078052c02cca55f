# Builds the package-arrow probes (test/suites/packaging.cmake) one after the other:
# every ALLOWED probe must compile, every FORBIDDEN one must fail because its
# header is not on the package's include path.
#   cmake -DBUILD_DIR=<build tree> -DALLOWED=a|b -DFORBIDDEN=c:header|d:header -P CheckPackageArrows.cmake
string(REPLACE "|" ";" allowed "${ALLOWED}")
string(REPLACE "|" ";" forbidden "${FORBIDDEN}")
set(failures 0)
foreach(target ${allowed})
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${target}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc EQUAL 0)
    message(STATUS "ok: ${target} compiles (the arrows allow it)")
  else()
    message(STATUS "FAIL: ${target} should compile:\n${out}")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
foreach(item ${forbidden})
  string(REPLACE ":" ";" parts "${item}")
  list(GET parts 0 target)
  list(GET parts 1 header)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${target}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0 AND out MATCHES "${header}: No such file or directory")
    message(STATUS "ok: ${target} does not compile: ${header} is not on its include path")
  else()
    message(STATUS "FAIL: ${target} should fail to find ${header} (exit ${rc}):\n${out}")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} package-arrow probe(s) failed")
endif()
