# Debian's fuzzylite (GPL) is the reference oracle: only the tests and fuzzygait-bench link it.
# Without it the build still works; those parts are skipped with a message.
find_path(FUZZYLITE_INCLUDE_DIR fl/Headers.h)
find_library(FUZZYLITE_LIBRARY fuzzylite)
find_program(FUZZYLITE_PROGRAM fuzzylite)
set(FUZZYLITE_EXAMPLES_DIR /usr/share/doc/fuzzylite/examples CACHE PATH
    "fuzzylite's example engines and datasets")
if(FUZZYLITE_INCLUDE_DIR AND FUZZYLITE_LIBRARY)
  set(FUZZYGAIT_HAVE_FUZZYLITE ON)
  add_library(fuzzylite_oracle INTERFACE)
  target_include_directories(fuzzylite_oracle SYSTEM INTERFACE ${FUZZYLITE_INCLUDE_DIR})
  target_link_libraries(fuzzylite_oracle INTERFACE ${FUZZYLITE_LIBRARY})
  message(STATUS "fuzzylite oracle: ${FUZZYLITE_LIBRARY}")
else()
  set(FUZZYGAIT_HAVE_FUZZYLITE OFF)
  message(STATUS "fuzzylite not found: conformance tests and fuzzygait-bench are skipped "
                 "(install libfuzzylite-dev, see scripts/install-deps.sh)")
endif()
