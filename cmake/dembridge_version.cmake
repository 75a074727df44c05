# dembridge_add_version(TARGET SOURCE): SOURCE (a small .cc) sees DEMBRIDGE_VERSION (CMake's
# project() version) and, through the generated header dembridge_git_commit.h, the git commit
# of the source tree at build time (cmake/git_commit.cmake; "unknown" without git or .git).
function(dembridge_add_version target source)
  set(_gen ${CMAKE_CURRENT_BINARY_DIR}/generated)
  add_custom_target(${target}_git_commit
    COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
            -DOUT=${_gen}/dembridge_git_commit.h -P ${PROJECT_SOURCE_DIR}/cmake/git_commit.cmake
    BYPRODUCTS ${_gen}/dembridge_git_commit.h
    COMMENT "git commit for --version")
  add_dependencies(${target} ${target}_git_commit)
  set_source_files_properties(${source} PROPERTIES
    COMPILE_DEFINITIONS "DEMBRIDGE_VERSION=\"${PROJECT_VERSION}\""
    INCLUDE_DIRECTORIES ${_gen})
endfunction()
