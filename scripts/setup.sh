#!/usr/bin/env bash
# Installs the Debian packages quadcover needs (only those missing) and builds it in build/ (Release).
# Usage: bash scripts/setup.sh          everything the test suite needs (scripts/run_tests.sh): all packages, all
#                                       targets (tests, benchmarks, the Python module)
#        bash scripts/setup.sh --main   only what the main job needs (scripts/run_main.sh): the CLI's packages and
#                                       the `quadcover` target
# Idempotent; safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."
MODE=tests
case "${1:-}" in
  --main) MODE=main ;;
  --tests | "") ;;
  *) echo "usage: bash scripts/setup.sh [--main|--tests]" >&2; exit 2 ;;
esac

# The CLI. libopenblas0-pthread: an optimized BLAS/LAPACK behind CHOLMOD's supernodal factorizations (through
# Debian's alternatives; the reference BLAS is 2-3x slower there). Serial: deterministic, and our TBB loops own the
# cores.
MAIN_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas0-pthread libtbb-dev libcli11-dev nlohmann-json3-dev
  libpng-dev libstb-dev libfplll-dev python3
)
# The test suite: GoogleTest, benchmarks, the Python module and its tests (pytest, meshio), pip in a venv
# (setuptools, wheel), quadcover.distributed (Dask), the Blender add-on (Debian's blender 3.4 runs python3.11),
# sanitizer and fuzz builds (clang).
TEST_PACKAGES=(
  libgtest-dev libbenchmark-dev libfmt-dev libspdlog-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-meshio
  python3-venv python3-pip python3-setuptools python3-wheel
  python3-distributed
  blender
  clang libclang-rt-14-dev
)
PACKAGES=("${MAIN_PACKAGES[@]}")
[ "$MODE" = tests ] && PACKAGES+=("${TEST_PACKAGES[@]}")
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# three.js for the HTML report is vendored in html/vendor (MIT); re-fetch it from npm if it is missing.
[ -f html/vendor/three.module.min.js ] || bash html/update_three.sh
JOBS=${JOBS:-$(nproc)}
if [ "$MODE" = main ]; then
  # A first configure of build/ leaves out tests, benchmarks and the module (their packages may be missing);
  # an existing build/ keeps its options. Only the CLI is built.
  OPTIONS=()
  [ -f build/CMakeCache.txt ] ||
    OPTIONS=(-DQUADCOVER_BUILD_TESTS=OFF -DQUADCOVER_BUILD_BENCH=OFF -DQUADCOVER_BUILD_PYTHON=OFF)
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${OPTIONS[@]}" ${QUADCOVER_CMAKE_ARGS:-} >/dev/null
  cmake --build build --target quadcover -j"$JOBS"
  exit 0
fi
# The Python module is part of the main build (for Debian's /usr/bin/python3), so tests need no second build.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DQUADCOVER_BUILD_TESTS=ON -DQUADCOVER_BUILD_BENCH=ON \
  -DQUADCOVER_BUILD_PYTHON=ON -DPython_EXECUTABLE=/usr/bin/python3 ${QUADCOVER_CMAKE_ARGS:-} >/dev/null
cmake --build build -j"$JOBS"
