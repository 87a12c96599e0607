#!/usr/bin/env bash
# The Python module: configure build-python with QUADCOVER_BUILD_PYTHON=ON for Debian's /usr/bin/python3, build the
# module, and run its pytest suite (python/tests) with /usr/bin/python3 (the python3 first on PATH may lack numpy).
set -euo pipefail
cd "$(dirname "$0")/../.."
PY=/usr/bin/python3
"$PY" -c "import numpy, pytest" 2>/dev/null || { echo "30_python: $PY needs python3-numpy and python3-pytest (scripts/setup.sh)"; exit 1; }
cmake -S . -B build-python -G Ninja -DCMAKE_BUILD_TYPE=Release -DQUADCOVER_BUILD_PYTHON=ON \
  -DQUADCOVER_BUILD_TESTS=OFF -DQUADCOVER_BUILD_BENCH=OFF -DPython_EXECUTABLE="$PY" >/dev/null
cmake --build build-python --target quadcover_python -j"${JOBS:-$(nproc)}"
PYTHONPATH="$PWD/build-python/python" "$PY" -m pytest -q python/tests
