#!/usr/bin/env bash
# quadcover.distributed on a 2-worker Dask LocalCluster (Debian's python3-distributed, installed here if missing):
# shipped meshes, a broken file and a file killed mid-run, the summary CSV/JSON, then a resumed run (python/tests/dask).
set -euo pipefail
cd "$(dirname "$0")/../.."
PY=/usr/bin/python3
BUILD=${QUADCOVER_PY_BUILD:-build}
if ! "$PY" -c "import distributed" 2>/dev/null; then
  echo "32_dask: installing python3-distributed"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  if ! { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
         --no-install-recommends python3-distributed >/dev/null; }; then
    echo "32_dask: SKIPPED: python3-distributed cannot be installed here (apt-get failed)"; exit 0
  fi
fi
cmake --build "$BUILD" --target quadcover quadcover_python -j"${JOBS:-$(nproc)}" >/dev/null
PYTHONPATH="$PWD/$BUILD/python" "$PY" -m pytest -q -p no:cacheprovider python/tests/dask
