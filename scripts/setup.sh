#!/usr/bin/env bash
# Installs the Debian packages quadcover needs (only those missing) and builds it in build/ (Release).
# Usage: bash scripts/setup.sh            (idempotent; safe to run again)
set -euo pipefail
cd "$(dirname "$0")/.."

# libopenblas0-pthread: an optimized BLAS/LAPACK behind CHOLMOD's supernodal factorizations (through Debian's
# alternatives; the reference BLAS is 2-3x slower there). Serial: deterministic, and our TBB loops own the cores.
PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas0-pthread libtbb-dev libcli11-dev nlohmann-json3-dev libfmt-dev libspdlog-dev
  libpng-dev libstb-dev libgtest-dev libbenchmark-dev libfplll-dev
  pybind11-dev python3-dev python3-numpy python3-pytest
  clang libclang-rt-14-dev
)
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
# The Python module is part of the main build (for Debian's /usr/bin/python3), so tests need no second build.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DQUADCOVER_BUILD_PYTHON=ON -DPython_EXECUTABLE=/usr/bin/python3 \
  ${QUADCOVER_CMAKE_ARGS:-} >/dev/null
cmake --build build -j"$JOBS"
