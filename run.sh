#!/usr/bin/env bash
# fuzzygait's two entry points (see README):
#   ./run.sh          installs what is missing, builds, and walks the default character (out/)
#   ./run.sh test     installs what is missing, builds, and runs every test
#                     (Release build, ASan+UBSan build, libFuzzer runs of the FLL reader,
#                     the FLD reader and the formula compiler)
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
    echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
    configure_and_build build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFUZZYGAIT_SANITIZE=ON \
      -DFUZZYGAIT_BUILD_BENCH=OFF -DFUZZYGAIT_REQUIRE_FUZZYLITE=ON
    (cd "$root/build-sanitize" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --output-on-failure -j "$jobs" -LE slow)
    echo "== libFuzzer runs of the FLL reader, the FLD reader and the formula compiler (clang)"
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
