#!/usr/bin/env bash
# The Python module, built by scripts/setup.sh in build/ (QUADCOVER_BUILD_PYTHON=ON, Debian's /usr/bin/python3); runs its
# pytest suite (python/tests) with /usr/bin/python3 (the python3 first on PATH may lack numpy).
set -euo pipefail
cd "$(dirname "$0")/../.."
PY=/usr/bin/python3
"$PY" -c "import numpy, pytest" 2>/dev/null || { echo "30_python: $PY needs python3-numpy and python3-pytest (scripts/setup.sh)"; exit 1; }
# scripts/setup.sh builds the module in the main Release build (build/python); build it there if missing.
BUILD=${QUADCOVER_PY_BUILD:-build}
cmake --build "$BUILD" --target quadcover quadcover_python -j"${JOBS:-$(nproc)}"  # the CLI: python -m quadcover
PYTHONPATH="$PWD/$BUILD/python" "$PY" -m pytest -q python/tests --ignore=python/tests/dask  # dask: 32_dask.sh
