#!/usr/bin/env bash
# fuzzygait's two entry points (see README):
#   ./run.sh          installs what is missing, builds, and walks the default character (out/)
#   ./run.sh test     installs what is missing, builds, and runs every test
#                     (Release build, ASan+UBSan build with the scalar lanes, a Clang build's
#                     walker, crowd, controller and lane tests, libFuzzer runs of the FLL,
#                     FLD and BVH readers and the formula compiler)
set -euo pipefail
cd "$(dirname "$0")"
root=$(pwd)
jobs=$(nproc 2>/dev/null || echo 2)

"$root/scripts/install-deps.sh"

configure_and_build() {  # dir, extra cmake args...
  local dir=$1
  shift
  cmake -S "$root" -B "$root/$dir" -G Ninja -DFUZZYGAIT_WERROR=ON "$@" >/dev/null
  cmake --build "$root/$dir" -j "$jobs"
}

mode=${1:-main}
case "$mode" in
  main)
    configure_and_build build -DCMAKE_BUILD_TYPE=Release
    echo "== walking the built-in default: 1.75 m tall, 0.70 m steps, 10 gait cycles"
    "$root/build/fuzzygait" walk -o "$root/out/walk"
    echo "== open out/walk.poses.svg in a browser to watch it, out/walk.svg for the curves"
    ;;
  test)
    echo "== Release build and tests"
    # fuzzylite is installed above: its conformance tests must run, not be skipped.
    configure_and_build build -DCMAKE_BUILD_TYPE=Release -DFUZZYGAIT_REQUIRE_FUZZYLITE=ON
    (cd "$root/build" && ctest --output-on-failure -j "$jobs")
    echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests (scalar lanes)"
    # FUZZYGAIT_SIMD=scalar: the vector code runs on the lanes' plain scalar bodies, so the golden
    # walks, the crowd and the packed controllers are checked end to end on the reference too.
    configure_and_build build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFUZZYGAIT_SANITIZE=ON \
      -DFUZZYGAIT_BUILD_BENCH=OFF -DFUZZYGAIT_REQUIRE_FUZZYLITE=ON -DFUZZYGAIT_SIMD=scalar
    (cd "$root/build-sanitize" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --output-on-failure -j "$jobs" -LE slow)
    echo "== Clang Release build: walker, crowd, controller and lane tests, the same golden bits"
    # The lanes' fast paths (SSE2, AVX2, AVX-512) as Clang compiles them; only the tests that walk,
    # evaluate controllers or check the lanes, run straight from their binaries.
    cmake -S "$root" -B "$root/build-clang" -G Ninja -DFUZZYGAIT_WERROR=ON \
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ -DFUZZYGAIT_BUILD_BENCH=OFF >/dev/null
    clang_tests=(gait_tests fuzzy_tests simd_tests rig_tests common_tests)
    cmake --build "$root/build-clang" -j "$jobs" --target "${clang_tests[@]}"
    for test in "${clang_tests[@]}"; do
      "$root/build-clang/tests/$test" --gtest_brief=1
    done
    echo "== libFuzzer runs of the FLL, FLD and BVH readers and the formula compiler (clang)"
    configure_and_build build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
      -DFUZZYGAIT_FUZZ=ON
    (cd "$root/build-fuzz" && ctest --output-on-failure -L fuzz)
    echo "== all tests passed"
    ;;
  *)
    echo "usage: $0 [test]" >&2
    exit 2
    ;;
esac
