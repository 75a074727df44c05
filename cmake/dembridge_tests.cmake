# Tests of how dembridge meets its input, shared by the test folders (tests/*/CMakeLists.txt).
#
# dembridge_expect_error(NAME OUTPUT REGEX ARGS...): runs `dembridge ARGS` into OUTPUT and passes
# when it is refused as bad input must be (tests/app/expect_error.sh): one line on stderr that
# matches REGEX, exit code 1, no output that looks complete.
function(dembridge_expect_error name output regex)
  cmake_parse_arguments(PARSE_ARGV 3 _dembridge "" "" "") # keeps a ';' inside an argument
  add_test(NAME ${name}
           COMMAND ${PROJECT_SOURCE_DIR}/tests/app/expect_error.sh $<TARGET_FILE:dembridge>
                   ${output} "${regex}" ${_dembridge_UNPARSED_ARGUMENTS})
endfunction()

# dembridge_expect_warning(NAME OUTPUT REGEX ARGS...): runs `dembridge ARGS` into OUTPUT and
# passes when the run completes (exit code 0) with a "dembridge: warning:" line on stderr that
# matches REGEX, the same warning recorded in summary.json (tests/coupling/expect_warning.sh).
function(dembridge_expect_warning name output regex)
  cmake_parse_arguments(PARSE_ARGV 3 _dembridge "" "" "")
  add_test(NAME ${name}
           COMMAND ${PROJECT_SOURCE_DIR}/tests/coupling/expect_warning.sh $<TARGET_FILE:dembridge>
                   ${output} "${regex}" ${_dembridge_UNPARSED_ARGUMENTS})
endfunction()
