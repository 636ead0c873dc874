#!/usr/bin/env bash
# Installs every Debian package that fuzzygait's build, tests and benchmarks need.
# Idempotent: does nothing when all are present. Run as root (apt-get).
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git
  clang libclang-rt-14-dev         # libFuzzer target for the FLL reader
  clang-format                     # the sources' format check (version 14 on Debian 12)
  # libraries (MIT/BSD/Apache: may be linked into the library and the program)
  libeigen3-dev nlohmann-json3-dev libcli11-dev libceres-dev
  libtinygltf-dev                  # glTF export (MIT; a shared library, pulls in libstb0)
  libcpp-httplib-dev               # the studio's HTTP server (MIT; pulls in OpenSSL, zlib, Brotli)
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # the Blender add-on's tests (apps/blender) and the BVH and glTF import checks; Debian's
  # Blender runs Debian's python3, so it loads the module built for it (a large download)
  blender
  # GPL reference oracle: linked only by the tests and by fuzzygait-bench
  libfuzzylite-dev fuzzylite
  # the studio's page (npm lock file in studio/), the BVH and glTF import checks (tests/js)
  nodejs npm
  chromium                         # the studio's browser test (tests/studio), headless
  # the mocap reader's reference extractor (tests/tools/bvh_sagittal.py), run by the tests
  python3
  # the Python module, import fuzzygait (apps/python; built for /usr/bin/python3), and its tests
  pybind11-dev python3-dev python3-numpy python3-pytest
  python3-distributed              # fuzzygait_dask: training on a Dask cluster (and its tests)
)

# A Node.js installed otherwise counts: NodeSource's nodejs package bundles npm and conflicts with
# Debian's npm package, so asking apt for npm there would fail.
installed() {
  case "$1" in
    nodejs) command -v node >/dev/null && return 0 ;;
    npm) command -v npm >/dev/null && return 0 ;;
  esac
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}

missing=()
for p in "${packages[@]}"; do
  if ! installed "$p"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  exit 0
fi
if [[ $(id -u) -ne 0 ]]; then
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "install-deps: run as root (or: sudo $0)" >&2
  exit 1
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
