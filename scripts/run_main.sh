#!/usr/bin/env bash
# The main job: installs what the CLI needs, builds only the CLI (build/quadcover), runs the whole pipeline on the
# Stanford bunny shipped in tests/data, and says where the results are. The test suite is scripts/run_tests.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --main
mkdir -p out
QC=./build/quadcover
MESH=tests/data/bunny_3k.obj

# ---- Main job: field -> parameterization -> quad mesh (+ HTML report), each with its JSON report in out/
echo "quadcover: $MESH -> out/"
$QC field "$MESH" -o out/bunny_3k.field.json -q
$QC param "$MESH" -o out/bunny_3k.param.obj --report out/bunny_3k.param.json -q
t0=$(date +%s%N)
$QC remesh "$MESH" -o out/bunny_3k.quad.obj --report out/bunny_3k.remesh.json --report-html out/bunny_3k.remesh.html -q
t1=$(date +%s%N)
$QC metrics out/bunny_3k.quad.obj --ref "$MESH" --report out/bunny_3k.metrics.json -q
/usr/bin/python3 - out/bunny_3k.remesh.json $(((t1 - t0) / 1000000)) <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
ms = int(sys.argv[2])
q, p = r["quad_mesh"], r["parameterization"]
print(f"  bunny_3k: {q['quads']} quads ({q['non_quads']} other faces), {q['vertices']} vertices, "
      f"{q['irregular_vertices']} irregular; RSD edge {q['rsd_edge_length']:.1f} %, angle "
      f"{q['rsd_corner_angle']:.1f} %; {p['branch_points']} branch points, {p['flipped_triangles']} flips; "
      f"remesh {ms / 1000:.1f} s")
PY
echo "  results: out/bunny_3k.quad.obj (quads), out/bunny_3k.param.obj (seamless UVs), out/bunny_3k.remesh.html"
echo "           (open in a browser), JSON reports out/bunny_3k.{field,param,remesh,metrics}.json"

# ---- Quick checks of these commands on two shipped meshes and the quality baseline (the full suite is
# `bash scripts/run_tests.sh`).
E2E_METRICS=$(mktemp --suffix=.json)
trap 'rm -f "$E2E_METRICS"' EXIT
/usr/bin/python3 tests/e2e/e2e.py --bin "$QC" --meshes bunny_3k,torus_5k --no-bad --metrics-out "$E2E_METRICS"
/usr/bin/python3 tests/regression/check_regression.py "$E2E_METRICS" --subset
