# Warnings and sanitizers, applied to every fuzzygait target.
set(FUZZYGAIT_WARNINGS
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Wnon-virtual-dtor
  -Wold-style-cast -Woverloaded-virtual -Wimplicit-fallthrough)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  # GCC 12 reports false -Wrestrict positives inside std::string concatenation (GCC PR 105329).
  list(APPEND FUZZYGAIT_WARNINGS -Wno-restrict)
endif()
if(FUZZYGAIT_WERROR)
  list(APPEND FUZZYGAIT_WARNINGS -Werror)
endif()

# Results equal fuzzylite's only if every a * b + c rounds twice, as written: no fused
# multiply-add, which GCC and Clang would otherwise contract to on targets that have one
# (-march=native and the like).
# No code here reads errno or the floating-point exception flags, so the compiler may drop the
# errno path of sqrt and speculate divisions into selects: the same values, and a walker step about
# 1 % faster (interleaved A/B of 2.4 M steps, medians 246.2 -> 244.3 ns; walks bit-identical).
set(FUZZYGAIT_FLOATING_POINT
  "$<$<CXX_COMPILER_ID:GNU,Clang,AppleClang>:-ffp-contract=off;-fno-math-errno;-fno-trapping-math>")

function(fuzzygait_configure_target target)
  target_compile_options(${target} PRIVATE ${FUZZYGAIT_WARNINGS} ${FUZZYGAIT_FLOATING_POINT})
  if(FUZZYGAIT_SANITIZE)
    target_compile_options(${target} PRIVATE
      -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      # GCC 12's flow analysis under ASan reports uninitialised members inside libstdc++
      # (std::function in <regex>) that are not; the Release build keeps the warning.
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# A library part of fuzzygait (one per folder under src/), installed and exported.
function(fuzzygait_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_library(fuzzygait_${name} STATIC ${ARG_SOURCES})
  add_library(fuzzygait::${name} ALIAS fuzzygait_${name})
  target_include_directories(fuzzygait_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(fuzzygait_${name} PUBLIC ${ARG_DEPENDS})
  set_target_properties(fuzzygait_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON
                        EXPORT_NAME ${name})
  fuzzygait_configure_target(fuzzygait_${name})
  set_property(GLOBAL APPEND PROPERTY FUZZYGAIT_LIBRARIES fuzzygait_${name})
endfunction()
