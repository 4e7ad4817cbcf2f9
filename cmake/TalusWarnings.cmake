# Warnings as errors for the project's own targets: talus_warnings(<target>).
# -Wno-restrict: GCC 12 reports false positives inside std::string concatenation at -O2
# (GCC bug 105329); nothing in Talus uses restrict.
function(talus_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                         -Wno-sign-conversion -Werror)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
endfunction()
