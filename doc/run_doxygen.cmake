# Runs Doxygen on DOXYFILE, whose warnings go to the file WARNINGS (its WARN_LOGFILE) and whose
# HTML goes to HTML_DIR, and prints the warnings. With STRICT, fails if there is any: the test
# doc_no_warnings.
#
#   cmake -DDOXYGEN=... -DDOXYFILE=... -DWARNINGS=... -DHTML_DIR=... [-DSTRICT=ON] -P run_doxygen.cmake

if(NOT DOXYGEN OR NOT EXISTS "${DOXYGEN}")
  if(STRICT)
    # The test doc_no_warnings, whose SKIP_REGULAR_EXPRESSION matches this line: CTest lists it
    # as skipped (doc/CMakeLists.txt), not as passed or failed.
    message(NOTICE "doc_no_warnings skipped: Doxygen not found (install doxygen with tools/install_dependencies.sh)")
  endif()
  message(FATAL_ERROR "Doxygen is not where the project was configured to find it (${DOXYGEN}): "
                      "install it (tools/install_dependencies.sh) and configure again")
endif()

file(REMOVE ${WARNINGS})
execute_process(COMMAND ${DOXYGEN} ${DOXYFILE} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "Doxygen failed (${result})")
endif()

# A concept is documented as a class of a file of doc/, not of a header: drop the #include
# line that Doxygen writes on its page.
file(GLOB pages ${HTML_DIR}/class*.html)
foreach(page ${pages})
  file(READ ${page} html)
  string(REGEX REPLACE "<p><code>#include &lt;[^&]*/Concepts/[^&]*&gt;</code></p>\n?" "" stripped "${html}")
  if(NOT stripped STREQUAL html)
    file(WRITE ${page} "${stripped}")
  endif()
endforeach()

if(EXISTS ${WARNINGS})
  file(READ ${WARNINGS} log)
endif()
string(STRIP "${log}" log)
if(log)
  string(REGEX MATCHALL "warning:" found "${log}")
  list(LENGTH found count)
  message(NOTICE "${log}")
  if(STRICT)
    message(FATAL_ERROR "Doxygen printed ${count} warning(s), listed above and in ${WARNINGS}")
  endif()
  message(WARNING "Doxygen printed ${count} warning(s), listed above and in ${WARNINGS}")
endif()
message(STATUS "Manual: ${HTML_DIR}/index.html")
