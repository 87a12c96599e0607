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
LOG=$(mktemp)
trap 'rm -f "$CURRENT" "$LOG"' EXIT
e2e_status=0
REG_ARGS=()
"$PY" tests/e2e/e2e.py --bin "$BIN" --jobs 2 --determinism --metrics-out "$CURRENT" 2>&1 | tee "$LOG" || e2e_status=$?
if ((e2e_status)); then
  # Known open defects are listed in tests/e2e/known_failures.txt; anything else fails the step.
  known=$(grep -v '^#' tests/e2e/known_failures.txt | awk 'NF{print $1}')
  failed=$(grep '^FAIL ' "$LOG" | awk '{print $2}' | tr -d ':' | sort -u)
  unexpected=$(comm -23 <(echo "$failed" | sort -u) <(echo "$known" | sort -u) | grep . || true)
  if [ -z "$failed" ] || [ -n "$unexpected" ]; then
    echo "50_e2e: unexpected failures: ${unexpected:-see above}" >&2
    exit 1
  fi
  echo "50_e2e: only known failures (tests/e2e/known_failures.txt): $(echo $failed)"
  REG_ARGS=(--subset)  # the known-failing meshes have no metrics; all others are still checked
fi
"$PY" tests/regression/check_regression.py "$CURRENT" "${REG_ARGS[@]}"
