# libFuzzer targets of the input readers (tests/fuzz, docs/fuzzing.md) when TALUS_FUZZ is on:
# clang's -fsanitize=fuzzer with AddressSanitizer and UndefinedBehaviorSanitizer. Every target
# is instrumented for coverage (fuzzer-no-link); only the fuzz targets link libFuzzer's main.
if(TALUS_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TALUS_FUZZ needs clang's libFuzzer: configure with -DCMAKE_C_COMPILER=clang "
                        "-DCMAKE_CXX_COMPILER=clang++ (scripts/fuzz.sh does)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer -gline-tables-only)
  # The sanitizers' checks keep clang from vectorising the `#pragma omp simd` loops of the mud
  # flow, which it reports as a warning (an error under -Werror); the fuzz targets never run them.
  add_compile_options(-Wno-pass-failed)
  add_link_options(-fsanitize=address,undefined)
endif()
