#!/usr/bin/env bash
# End-to-end suite (tests/e2e/e2e.py, Debian's /usr/bin/python3, standard library only): every shipped mesh through
# info, field, param, remesh and metrics with independent re-checks of the written files (seamless map, manifold
# quad mesh, counts vs. reports); every bad/ mesh exits 2 with a file:line message and leaves no file; determinism
# (byte-identical outputs twice and in batch -j2). Then the quality regression check against
# tests/regression/metrics.json (update deliberately with scripts/update_regression.sh).
# All meshes run every command; about 1-2 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/../.."
BIN=${QUADCOVER_BIN:-build/quadcover}
PY=/usr/bin/python3
CURRENT=$(mktemp --suffix=.json)
trap 'rm -f "$CURRENT"' EXIT
"$PY" tests/e2e/e2e.py --self-test
"$PY" tests/regression/check_regression.py --self-test
"$PY" tests/e2e/e2e.py --bin "$BIN" --jobs 2 --determinism --metrics-out "$CURRENT"
"$PY" tests/regression/check_regression.py "$CURRENT"
