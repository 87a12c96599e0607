#!/usr/bin/env bash
# Rewrites the quality baseline tests/regression/metrics.json from the current build (rules, tolerances and
# known_issues are kept; only the per-mesh values change). Use it when quality changed on purpose, then commit
# tests/regression/metrics.json saying why.
# Usage: bash scripts/update_regression.sh            (uses build/quadcover; QUADCOVER_BIN=... to choose another)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${QUADCOVER_BIN:-build/quadcover}
PY=/usr/bin/python3
CURRENT=$(mktemp --suffix=.json)
trap 'rm -f "$CURRENT"' EXIT
# The end-to-end checks must pass first: a baseline is only taken from valid outputs.
"$PY" tests/e2e/e2e.py --bin "$BIN" --no-bad --metrics-out "$CURRENT"
"$PY" tests/regression/check_regression.py "$CURRENT" --update \
  --note "$(date -u +%Y-%m-%d) by scripts/update_regression.sh at $(git rev-parse --short HEAD 2>/dev/null || echo '?')"
git --no-pager diff --stat -- tests/regression/metrics.json || true
