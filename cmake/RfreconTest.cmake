# rfrecon_add_test(NAME SOURCES... [LABELS l...] [FIXTURES f]): one GoogleTest executable registered with ctest.
# Label "kernel" marks tests that run OpenCL kernels (.ci/run runs those again under oclgrind); label "accuracy"
# marks end-to-end accuracy tests on rendered scenes (skipped in the sanitizer pass for time). FIXTURES names the ctest
# fixture (e.g. a rendered scene) the tests need; it may REQUIRE others.
include(GoogleTest)
function(rfrecon_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LABELS;FIXTURES" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE rfrecon::rfrecon GTest::gtest GTest::gtest_main GTest::gmock)
  target_compile_options(${name} PRIVATE -Wall -Wextra)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  target_compile_definitions(${name} PRIVATE RFRECON_FIXTURES_DIR="${CMAKE_BINARY_DIR}/fixtures"
                                             RFRECON_CLI_PATH="$<TARGET_FILE:rfrecon_cli>"
                                             RFRECON_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  add_dependencies(${name} rfrecon_cli)
  # gtest_discover_tests keeps only the first element of a list property: tests name one fixture, which REQUIRES
  # the others (ctest sets up required fixtures transitively).
  list(LENGTH ARG_FIXTURES fixture_count)
  if(fixture_count GREATER 1)
    message(FATAL_ERROR "${name}: name one fixture and chain the others with REQUIRES")
  endif()
  gtest_discover_tests(${name} PROPERTIES FIXTURES_REQUIRED "${ARG_FIXTURES}" DISCOVERY_TIMEOUT 60
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
  # Labels are a list, so they are set by a script ctest reads after the discovered tests (${name}_TESTS).
  if(ARG_LABELS)
    set(labels_script ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
    file(WRITE ${labels_script}
         "if(${name}_TESTS)\n  set_tests_properties(\${${name}_TESTS} PROPERTIES LABELS \"${ARG_LABELS}\")\nendif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${labels_script})
  endif()
endfunction()

# rfrecon_add_fixture(NAME COMMAND... [REQUIRES f...]): a ctest fixture setup step (e.g. `rfrecon simulate`), run
# once before the tests that name it in FIXTURES; labelled "accuracy".
function(rfrecon_add_fixture name)
  cmake_parse_arguments(ARG "" "" "COMMAND;REQUIRES" ${ARGN})
  add_test(NAME fixture_${name} COMMAND ${ARG_COMMAND})
  set_tests_properties(fixture_${name} PROPERTIES FIXTURES_SETUP ${name} FIXTURES_REQUIRED "${ARG_REQUIRES}"
    LABELS accuracy TIMEOUT 1200)
endfunction()
