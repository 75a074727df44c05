# The helpers the test folders share (tests/*/CMakeLists.txt): one call per test, its command
# and the properties it needs. First the refusals and warnings of bad input.
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
# single-copy shared memory in containers), the launcher, python3 for the checker scripts, a test
# that cannot run here shown as skipped, and the run-then-check shape of most app-level tests.
set(DEMBRIDGE_MPI_ENV
    "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_btl_vader_single_copy_mechanism=none")
find_program(MPIEXEC_EXECUTABLE NAMES mpirun mpiexec)
find_program(DEMBRIDGE_PYTHON3 python3)

# dembridge_skipped_test(NAME REASON): a test that cannot run here (no mpirun, python3, ...)
# shows as skipped, not absent.
function(dembridge_skipped_test name reason)
  add_test(NAME ${name} COMMAND sh -c "echo '${reason}: skipped'; exit 77")
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77)
endfunction()

# dembridge_test(NAME COMMAND command... [MPI N] [TIMEOUT S] [PROCESSORS N] [SETUP FIXTURE]
#                [AFTER FIXTURES...] [DIR WORKING_DIRECTORY] [ENV VAR=VALUE...] [MPI_ENV]
#                [SKIP_RETURN_CODE C]): add_test with the properties the tests set, in one call.
# MPI N runs COMMAND under `mpirun -np N --oversubscribe` with Open MPI's environment (the test
# shows as skipped where mpirun is missing); MPI_ENV gives that environment to a command that
# starts mpirun itself or initialises MPI on one rank; SETUP makes the test the fixture FIXTURE,
# AFTER runs it once the fixtures it reads are done.
function(dembridge_test name)
  cmake_parse_arguments(PARSE_ARGV 1 T "MPI_ENV"
    "MPI;TIMEOUT;PROCESSORS;SETUP;DIR;SKIP_RETURN_CODE" "COMMAND;AFTER;ENV")
  set(command ${T_COMMAND})
  if(T_MPI)
    if(NOT MPIEXEC_EXECUTABLE)
      dembridge_skipped_test(${name} "mpirun not found")
      return()
    endif()
    set(command ${MPIEXEC_EXECUTABLE} -np ${T_MPI} --oversubscribe ${command})
    set(T_MPI_ENV TRUE)
  endif()
  if(T_DIR)
    add_test(NAME ${name} COMMAND ${command} WORKING_DIRECTORY ${T_DIR})
  else()
    add_test(NAME ${name} COMMAND ${command})
  endif()
  if(T_MPI_ENV)
    list(APPEND T_ENV ${DEMBRIDGE_MPI_ENV})
  endif()
  foreach(p TIMEOUT PROCESSORS SKIP_RETURN_CODE)
    if(T_${p})
      set_tests_properties(${name} PROPERTIES ${p} ${T_${p}})
    endif()
  endforeach()
  if(T_SETUP)
    set_tests_properties(${name} PROPERTIES FIXTURES_SETUP ${T_SETUP})
  endif()
  # the lists whole (one property value each)
  if(T_AFTER)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "${T_AFTER}")
  endif()
  if(T_ENV)
    set_tests_properties(${name} PROPERTIES ENVIRONMENT "${T_ENV}")
  endif()
endfunction()

# dembridge_expect_error_mpi(NAME NP OUTPUT REGEX ARGS...): dembridge_expect_error under
# `mpirun -np NP` on two processors (tests/app/expect_error_mpi.sh: exit code 1, one line on rank
# 0's stderr that matches REGEX, nothing on the other ranks', no folder); skipped without mpirun.
function(dembridge_expect_error_mpi name np output regex)
  cmake_parse_arguments(PARSE_ARGV 4 _dembridge "" "" "")
  if(NOT MPIEXEC_EXECUTABLE)
    dembridge_skipped_test(${name} "mpirun not found")
    return()
  endif()
  add_test(NAME ${name}
           COMMAND ${PROJECT_SOURCE_DIR}/tests/app/expect_error_mpi.sh ${MPIEXEC_EXECUTABLE} ${np}
                   $<TARGET_FILE:dembridge> ${output} "${regex}" ${_dembridge_UNPARSED_ARGUMENTS})
  set_tests_properties(${name} PROPERTIES PROCESSORS 2 ENVIRONMENT "${DEMBRIDGE_MPI_ENV}")
endfunction()

# dembridge_python_test(NAME SCRIPT ARGS... [dembridge_test keywords]): python3 runs SCRIPT (a
# checker, a driver) with ARGS; where python3 is missing the test shows as skipped.
function(dembridge_python_test name script)
  if(DEMBRIDGE_PYTHON3)
    dembridge_test(${name} COMMAND ${DEMBRIDGE_PYTHON3} ${script} ${ARGN})
  else()
    dembridge_skipped_test(${name} "python3 not found")
  endif()
endfunction()

# dembridge_check_output(NAME ARGS... [dembridge_test keywords]): tests/app/check_output.py ARGS,
# what a command prints and the files it leaves (its usage lists the checks).
function(dembridge_check_output name)
  dembridge_python_test(${name} ${PROJECT_SOURCE_DIR}/tests/app/check_output.py ${ARGN})
endfunction()

# dembridge_dealii_program(NAME SOURCES... [LINK libraries...]): a test program with deal.II's
# flags as the libraries have them (without deal.II's -std=c++17, which would undo C++20, and
# its -g); linked with the plain target_link_libraries signature, as deal_ii_setup_target is.
function(dembridge_dealii_program name)
  cmake_parse_arguments(T "" "" "LINK" ${ARGN})
  add_executable(${name} ${T_UNPARSED_ARGUMENTS})
  string(REPLACE "-std=c++17" "" DEAL_II_CXX_FLAGS "${DEAL_II_CXX_FLAGS}")
  string(REGEX REPLACE "(^| )-g( |$)" " " DEAL_II_CXX_FLAGS "${DEAL_II_CXX_FLAGS}")
  deal_ii_setup_target(${name})
  if(T_LINK)
    target_link_libraries(${name} ${T_LINK})
  endif()
endfunction()

# dembridge_set_arguments(VAR overrides...): VAR = `--set o1 --set o2 ...`.
function(dembridge_set_arguments var)
  set(args)
  foreach(s IN LISTS ARGN)
    list(APPEND args --set "${s}")
  endforeach()
  set(${var} ${args} PARENT_SCOPE)
endfunction()

# dembridge_run(TEST CASE OUTPUT [FIXTURE F] [SET overrides...] [dembridge_test keywords]): TEST
# runs `dembridge run CASE --output-dir OUTPUT --set ...` and sets up the fixture F (TEST's own
# name where F is not given) that checks require.
function(dembridge_run test case output)
  cmake_parse_arguments(T "MPI_ENV" "FIXTURE;MPI;TIMEOUT;PROCESSORS" "SET;AFTER;ENV" ${ARGN})
  dembridge_set_arguments(args ${T_SET})
  if(NOT T_FIXTURE)
    set(T_FIXTURE ${test})
  endif()
  set(keywords)
  foreach(k MPI TIMEOUT PROCESSORS)
    if(T_${k})
      list(APPEND keywords ${k} ${T_${k}})
    endif()
  endforeach()
  foreach(k AFTER ENV)
    if(T_${k})
      list(APPEND keywords ${k} ${T_${k}})
    endif()
  endforeach()
  if(T_MPI_ENV)
    list(APPEND keywords MPI_ENV)
  endif()
  dembridge_test(${test} COMMAND $<TARGET_FILE:dembridge> run ${case} --output-dir ${output}
                 ${args} SETUP ${T_FIXTURE} ${keywords})
endfunction()

# dembridge_check(TEST AFTER fixtures... COMMAND command... [dembridge_test keywords]): TEST runs
# COMMAND (check_summary's assertions on a summary.json, a checker script) once the runs it
# reads (fixtures) are done.
function(dembridge_check test)
  dembridge_test(${test} ${ARGN})
endfunction()
