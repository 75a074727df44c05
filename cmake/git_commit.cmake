# Writes ${OUT} (a C++ header) with the git commit of ${SOURCE_DIR}: run at every build by the
# target dembridge_git_commit, so the commit is current without reconfiguring. configure_file
# rewrites the header only when its text changes, so an unchanged commit rebuilds nothing.
# Without git or without .git (a release tarball) the commit reads "unknown".
set(DEMBRIDGE_GIT_COMMIT "unknown")
find_program(GIT_EXECUTABLE git)
if(GIT_EXECUTABLE AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND ${GIT_EXECUTABLE} -C "${SOURCE_DIR}" rev-parse HEAD
                  OUTPUT_VARIABLE _commit RESULT_VARIABLE _failed
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT _failed AND _commit)
    set(DEMBRIDGE_GIT_COMMIT "${_commit}")
    # tracked files changed since the commit: the binary is not exactly that commit
    execute_process(COMMAND ${GIT_EXECUTABLE} -C "${SOURCE_DIR}" diff --quiet HEAD --
                    RESULT_VARIABLE _dirty OUTPUT_QUIET ERROR_QUIET)
    if(_dirty EQUAL 1)
      string(APPEND DEMBRIDGE_GIT_COMMIT "-dirty")
    endif()
  endif()
endif()
configure_file("${SOURCE_DIR}/cmake/git_commit.h.in" "${OUT}" @ONLY)
