# Installs the runtime component of the fuzzygait build alone into a scratch prefix, then
# configures, builds and runs the game-side example against it with
# find_package(fuzzygait COMPONENTS runtime), as a game would, and the C examples (walk_in_c,
# walk_a_path_in_c); and checks that neither the installed runtime nor the example links any
# library but the C++ standard library's. Then the
# whole package: find_package(fuzzygait COMPONENTS offline) builds a program that records a walk.
# cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -P check_example.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/runtime")

include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)  # run(COMMAND...)

run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}" --component runtime)
# The runtime alone: its headers and its library, nothing of the tools.
file(GLOB_RECURSE installed RELATIVE "${prefix}" "${prefix}/*")
foreach(file IN LISTS installed)
  if(file MATCHES "fuzzygait/(eval|learn|io|plot)/|offline|bin/")
    message(FATAL_ERROR "the runtime component installed a file of the tools: ${file}")
  endif()
endforeach()
file(GLOB targets_file "${prefix}/lib*/cmake/fuzzygait/fuzzygaitRuntimeTargets.cmake")
file(READ "${targets_file}" targets)
if(targets MATCHES "INTERFACE_LINK_LIBRARIES")
  message(FATAL_ERROR "fuzzygait::runtime asks its users to link more libraries:\n${targets}")
endif()

run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/walk_in_game" -B "${WORK_DIR}/example"
    -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/example" --verbose)
# The link line: the example's object, the runtime's archive, nothing else.
string(REGEX MATCH "[^\n]*-o walk_in_game[^\n]*" link_line "${run_output}")
string(REGEX MATCHALL "[^ ]+\\.(a|so)|-l[^ ]+" linked "${link_line}")
if(NOT linked MATCHES "libfuzzygait_runtime\\.a" OR linked MATCHES ";")
  message(FATAL_ERROR "the example links more than the runtime: ${linked}\n${link_line}")
endif()
# The shared libraries the example needs at run time: the C and C++ standard libraries only.
find_program(READELF readelf)
if(READELF)
  run(${READELF} -d "${WORK_DIR}/example/walk_in_game")
  string(REGEX MATCHALL "Shared library: \\[[^]]+\\]" needed "${run_output}")
  foreach(library IN LISTS needed)
    if(NOT library MATCHES "\\[(libstdc\\+\\+|libm|libgcc_s|libc|ld-linux[^]]*)\\.so")
      message(FATAL_ERROR "the example needs ${library}: the runtime must need the C++ standard "
                          "library only")
    endif()
  endforeach()
endif()
run("${WORK_DIR}/example/walk_in_game")
if(NOT run_output MATCHES "left foot planted" OR NOT run_output MATCHES "t= 9")
  message(FATAL_ERROR "the example did not walk:\n${run_output}")
endif()
message(STATUS "the installed runtime builds and runs the example, linking ${linked}:\n"
               "${link_line}\n${run_output}")

# The path example, from the runtime component alone: the whole body round a corner.
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/walk_a_path" -B "${WORK_DIR}/example_path"
    -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/example_path")
run("${WORK_DIR}/example_path/walk_a_path")
if(NOT run_output MATCHES "left foot planted" OR NOT run_output MATCHES "path end \\(5\\.50, 4\\.50\\): reached")
  message(FATAL_ERROR "the path example did not walk its path:\n${run_output}")
endif()
message(STATUS "the installed runtime builds and runs the path example:\n${run_output}")

# The C example, from the runtime component alone: it walks, speeds up, has a bad request refused
# with its reason, and walks a crowd.
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/walk_in_c" -B "${WORK_DIR}/example_c"
    -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/example_c")
run("${WORK_DIR}/example_c/walk_in_c")
if(NOT run_output MATCHES "speed 1\\.80 m/s" OR NOT run_output MATCHES "refused: speed must be between"
   OR NOT run_output MATCHES "character 2 after 5 s")
  message(FATAL_ERROR "the C example did not walk as it should:\n${run_output}")
endif()
message(STATUS "the installed runtime builds and runs the C example:\n${run_output}")

# The C path example, from the runtime component alone: a skeleton given as arrays, mapped by its
# names, walked round an S and posed; a bad path refused with its reason.
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/walk_a_path_in_c" -B "${WORK_DIR}/example_path_c"
    -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/example_path_c")
run("${WORK_DIR}/example_path_c/walk_a_path_in_c")
if(NOT run_output MATCHES "leftUpperArm <- mixamorig:LeftArm"
   OR NOT run_output MATCHES "right foot planted"
   OR NOT run_output MATCHES "path end \\(3\\.00, 6\\.00\\): reached"
   OR NOT run_output MATCHES "refused: path point 3 is the same")
  message(FATAL_ERROR "the C path example did not walk its path as it should:\n${run_output}")
endif()
message(STATUS "the installed runtime builds and runs the C path example:\n${run_output}")

# The offline component: a program that records a walk and measures it.
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/all")
file(WRITE "${WORK_DIR}/offline/CMakeLists.txt" [=[
cmake_minimum_required(VERSION 3.25)
project(offline_user LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(fuzzygait 0.1 REQUIRED COMPONENTS offline)
add_executable(offline_user main.cpp)
target_link_libraries(offline_user PRIVATE fuzzygait::offline)
]=])
file(WRITE "${WORK_DIR}/offline/main.cpp" [=[
#include <fuzzygait/eval/evaluation.hpp>
#include <fuzzygait/eval/motion.hpp>
#include <cstdio>
int main() {
  using namespace fuzzygait;
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker walker(set, gait::WalkerOptions{}, ground);
  const eval::Motion motion = eval::record_cycles(walker, 3, 120.0);
  const eval::GaitReport report = eval::evaluate(motion, ground);
  std::printf("cadence %.1f\n", report.cadence);
  return report.cadence > 80.0 ? 0 : 1;
}
]=])
run(${CMAKE_COMMAND} -S "${WORK_DIR}/offline" -B "${WORK_DIR}/offline/build" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${WORK_DIR}/all")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/offline/build")
run("${WORK_DIR}/offline/build/offline_user")
message(STATUS "the offline component builds a program that measures a walk: ${run_output}")
