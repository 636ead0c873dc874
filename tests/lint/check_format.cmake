# Fails when a C++ source of the project differs from what clang-format makes of it (.clang-format
# at the top). Pinned to clang-format 14, Debian 12's, which install-deps.sh installs: other
# versions format some constructs differently, so with them the check is skipped.
#   cmake -DCLANG_FORMAT=<program or empty> -DSOURCE_DIR=<project> -P check_format.cmake
if(NOT CLANG_FORMAT)
  message("format check skipped: clang-format not found")
  return()
endif()
execute_process(COMMAND ${CLANG_FORMAT} --version OUTPUT_VARIABLE version)
if(NOT version MATCHES "version 14\\.")
  string(STRIP "${version}" version)
  message("format check skipped: it is pinned to clang-format 14, found ${version}")
  return()
endif()
set(files)
foreach(dir IN ITEMS apps bench examples fuzz include src tests)
  file(GLOB_RECURSE found ${SOURCE_DIR}/${dir}/*.cpp ${SOURCE_DIR}/${dir}/*.hpp
       ${SOURCE_DIR}/${dir}/*.h)
  list(APPEND files ${found})
endforeach()
list(LENGTH files count)
if(count EQUAL 0)
  message(FATAL_ERROR "no C++ sources found under ${SOURCE_DIR}")
endif()
execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${files}
                RESULT_VARIABLE result ERROR_VARIABLE diagnostics)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "not clang-formatted (run clang-format -i on these):\n${diagnostics}")
endif()
message("${count} sources clang-formatted")
