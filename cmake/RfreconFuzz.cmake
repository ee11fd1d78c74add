# RFRECON_FUZZ=ON (clang only): the sanitizer build of Sanitizers.cmake plus libFuzzer's coverage instrumentation
# (-fsanitize=fuzzer-no-link) in every target, and the libFuzzer targets of tests/fuzz/ (docs/fuzzing.md).
if(RFRECON_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT CMAKE_C_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "RFRECON_FUZZ=ON needs clang: -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++")
  endif()
  if(NOT RFRECON_BUILD_TESTS)
    message(FATAL_ERROR "RFRECON_FUZZ=ON needs RFRECON_BUILD_TESTS=ON (the fuzzers' ctest runs live in tests/)")
  endif()
  set(RFRECON_FUZZ_SECONDS 30 CACHE STRING "Seconds each fuzzer runs under ctest (environment variable overrides)")
  # Implied, so that Sanitizers.cmake instruments every target and the tests that skip sanitizer builds skip this one.
  set(RFRECON_SANITIZE ON)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
