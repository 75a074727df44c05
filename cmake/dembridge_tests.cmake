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

# What the test folders share beyond the refusals: Open MPI's environment here (as root, no
# single-copy shared memory in containers), the launcher, a test that cannot run here shown as
# skipped, and the run-then-check shape of most app-level tests.
set(DEMBRIDGE_MPI_ENV
    "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_btl_vader_single_copy_mechanism=none")
find_program(MPIEXEC_EXECUTABLE NAMES mpirun mpiexec)

# dembridge_skipped_test(NAME REASON): a test that cannot run here (no mpirun, python3, ...)
# shows as skipped, not absent.
function(dembridge_skipped_test name reason)
  add_test(NAME ${name} COMMAND sh -c "echo '${reason}: skipped'; exit 77")
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77)
endfunction()

# dembridge_set_arguments(VAR overrides...): VAR = `--set o1 --set o2 ...`.
function(dembridge_set_arguments var)
  set(args)
  foreach(s IN LISTS ARGN)
    list(APPEND args --set "${s}")
  endforeach()
  set(${var} ${args} PARENT_SCOPE)
endfunction()

# dembridge_run(TEST CASE OUTPUT [FIXTURE F] [MPI N] [SET overrides...]): TEST runs
# `dembridge run CASE --output-dir OUTPUT --set ...` (under `mpirun -np N --oversubscribe` with
# MPI) and sets up the fixture F (TEST's own name where F is not given) that checks require.
function(dembridge_run test case output)
  cmake_parse_arguments(T "" "FIXTURE;MPI" "SET" ${ARGN})
  dembridge_set_arguments(args ${T_SET})
  set(cmd $<TARGET_FILE:dembridge> run ${case} --output-dir ${output} ${args})
  if(T_MPI)
    set(cmd ${MPIEXEC_EXECUTABLE} -np ${T_MPI} --oversubscribe ${cmd})
  endif()
  if(NOT T_FIXTURE)
    set(T_FIXTURE ${test})
  endif()
  add_test(NAME ${test} COMMAND ${cmd})
  set_tests_properties(${test} PROPERTIES FIXTURES_SETUP ${T_FIXTURE})
endfunction()

# dembridge_check(TEST AFTER fixtures... COMMAND command...): TEST runs COMMAND (check_summary's
# assertions on a summary.json, a checker script) once the runs it reads (fixtures) are done.
function(dembridge_check test)
  cmake_parse_arguments(T "" "" "AFTER;COMMAND" ${ARGN})
  add_test(NAME ${test} COMMAND ${T_COMMAND})
  set_tests_properties(${test} PROPERTIES FIXTURES_REQUIRED "${T_AFTER}")
endfunction()
