# ctest driver of one fuzzer (tests/fuzz/CMakeLists.txt): runs FUZZER with OPTIONS ("|"-separated) for SECONDS
# (environment variable RFRECON_FUZZ_SECONDS overrides) over WORK_DIR/corpus, where new inputs go, and the seed
# corpus SEEDS, which it only reads. A finding is saved as WORK_DIR/crash-*, leak-*, timeout-* or oom-* and fails.
if(DEFINED ENV{RFRECON_FUZZ_SECONDS})
  set(SECONDS $ENV{RFRECON_FUZZ_SECONDS})
endif()
string(REPLACE "|" ";" OPTIONS "${OPTIONS}")
file(MAKE_DIRECTORY ${WORK_DIR}/corpus)
execute_process(COMMAND ${FUZZER} ${OPTIONS} -max_total_time=${SECONDS} -print_final_stats=1
                        -artifact_prefix=${WORK_DIR}/ ${WORK_DIR}/corpus ${SEEDS}
                RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${FUZZER} found a bug (exit ${result}); its input is in ${WORK_DIR}/. To keep it as a "
                      "regression test, copy it to tests/fuzz/regressions/ (docs/fuzzing.md).")
endif()
