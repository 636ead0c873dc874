# Runs a libFuzzer target for a bounded time on a fresh copy of its corpus, so the repository's
# corpus is never written, and fails when the fuzzer reports a crash, a timeout, running out of
# memory, a leak or a sanitizer error. Used by CTest (fuzz/CMakeLists.txt) as
#   cmake -DFUZZER=... -DCORPUS=... -DWORK=... -DSECONDS=... -DMAX_LEN=... [-DDICTIONARY=...]
#         -P RunFuzzer.cmake
foreach(variable FUZZER CORPUS WORK SECONDS MAX_LEN)
  if(NOT DEFINED ${variable} OR "${${variable}}" STREQUAL "")
    message(FATAL_ERROR "RunFuzzer.cmake: -D${variable}=... is missing")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/corpus" "${WORK}/artifacts")
file(COPY "${CORPUS}/" DESTINATION "${WORK}/corpus")

set(arguments "${WORK}/corpus" -max_total_time=${SECONDS} -timeout=10 -rss_limit_mb=2048
    -max_len=${MAX_LEN} -artifact_prefix=${WORK}/artifacts/ -print_final_stats=1)
if(DICTIONARY)
  list(APPEND arguments -dict=${DICTIONARY})
endif()
set(ENV{UBSAN_OPTIONS} "print_stacktrace=1")

message(STATUS "${FUZZER} ${arguments}")
execute_process(COMMAND "${FUZZER}" ${arguments} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  file(GLOB artifacts "${WORK}/artifacts/*")
  list(JOIN artifacts "\n  " artifact_list)
  message(FATAL_ERROR "the fuzzer failed (${result}). Inputs it kept:\n  ${artifact_list}\n"
                      "Reproduce with: ${FUZZER} <input>; once fixed, add the input to "
                      "${CORPUS} and a regression test to tests/fuzzy/.")
endif()
