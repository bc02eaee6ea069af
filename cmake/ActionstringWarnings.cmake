# Strict warnings for the project's own targets. The runtime's headers are
# compiled through every one of them; targets marked RUNTIME (header checks,
# runtime tests, firmware) also flag implicit float→double promotion, which
# costs a software double on a Cortex-M4F.
function(actionstring_set_warnings target)
  cmake_parse_arguments(ARG "RUNTIME" "" "" ${ARGN})
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                             -Wsign-conversion -Wold-style-cast)
    if(ARG_RUNTIME)
      target_compile_options(${target} PRIVATE -Wdouble-promotion)
    endif()
    if(ACTIONSTRING_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  endif()
endfunction()
