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

# The vector code's bodies (src/runtime/simd/lanes.hpp): auto compiles SSE2 lanes on x86-64 and,
# in translation units of their own, AVX2 ones that run where the processor has AVX2 (chosen at
# run time); scalar keeps the plain reference bodies only, with the same bits.
set(FUZZYGAIT_SIMD auto CACHE STRING
    "Vector code: auto (SSE2, and AVX2 where the CPU has it) or scalar")
set_property(CACHE FUZZYGAIT_SIMD PROPERTY STRINGS auto scalar)
if(NOT FUZZYGAIT_SIMD MATCHES "^(auto|scalar)$")
  message(FATAL_ERROR "FUZZYGAIT_SIMD must be auto or scalar, not '${FUZZYGAIT_SIMD}'")
endif()
# The flags of the AVX2 and AVX-512F translation units, empty where there are none.
set(FUZZYGAIT_AVX2_FLAG "")
set(FUZZYGAIT_AVX512_FLAG "")
if(FUZZYGAIT_SIMD STREQUAL "auto" AND CMAKE_SIZEOF_VOID_P EQUAL 8 AND
   CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64|x64)$")
  if(MSVC)
    set(FUZZYGAIT_AVX2_FLAG /arch:AVX2)
    set(FUZZYGAIT_AVX512_FLAG /arch:AVX512)
  elseif(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    set(FUZZYGAIT_AVX2_FLAG -mavx2)
    set(FUZZYGAIT_AVX512_FLAG -mavx512f)
  endif()
endif()

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

# A fuzzygait library (runtime, offline) or tool library (plot): static, position-independent,
# public headers under include/, the project's internal headers (src/, as "runtime/...") private.
function(fuzzygait_add_library target)
  cmake_parse_arguments(ARG "" "EXPORT_NAME" "SOURCES" ${ARGN})
  add_library(${target} STATIC ${ARG_SOURCES})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/src ${CMAKE_CURRENT_BINARY_DIR})
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  if(ARG_EXPORT_NAME)
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${ARG_EXPORT_NAME})
    add_library(fuzzygait::${ARG_EXPORT_NAME} ALIAS ${target})
  endif()
  fuzzygait_configure_target(${target})
endfunction()

# Text files compiled into a library as string literals (cmake/EmbedFiles.cmake), so it works
# without finding its data at run time. `header` is the include path of the declaring header.
function(fuzzygait_embed output header namespace source_dir)
  set(globs ${ARGN})
  list(TRANSFORM globs PREPEND "${source_dir}/" OUTPUT_VARIABLE absolute)
  file(GLOB inputs CONFIGURE_DEPENDS ${absolute})
  string(REPLACE ";" "\\;" globs_arg "${globs}")
  add_custom_command(OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${source_dir} "-DGLOBS=${globs_arg}" -DOUTPUT=${output}
            -DHEADER=${header} -DNAMESPACE=${namespace} -P ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    DEPENDS ${inputs} ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    COMMENT "Embedding ${header}")
endfunction()
