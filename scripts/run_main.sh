#!/usr/bin/env bash
# Set-up, build, and the main job on a mesh shipped in the repository.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out

# ---- Main job: the whole pipeline on the Stanford bunny (outputs and JSON reports in out/)
QC=./build/quadcover
$QC info tests/data/bunny_3k.obj
$QC field tests/data/bunny_3k.obj -o out/bunny_3k.field.json -q
$QC param tests/data/bunny_3k.obj -o out/bunny_3k.param.obj --report out/bunny_3k.param.json
$QC remesh tests/data/bunny_3k.obj -o out/bunny_3k.quad.obj --report out/bunny_3k.remesh.json
$QC metrics out/bunny_3k.quad.obj --ref tests/data/bunny_3k.obj

# ---- Test suite (quick): end-to-end checks of these commands on two shipped meshes and the quality baseline
# (the full suite is `bash scripts/run_tests.sh`).
E2E_METRICS=$(mktemp --suffix=.json)
trap 'rm -f "$E2E_METRICS"' EXIT
/usr/bin/python3 tests/e2e/e2e.py --bin "$QC" --meshes bunny_3k,torus_5k --no-bad --metrics-out "$E2E_METRICS"
/usr/bin/python3 tests/regression/check_regression.py "$E2E_METRICS" --subset
