#!/usr/bin/env bash
# `quadcover remesh` and `quadcover metrics` end to end: the written quad OBJ is a manifold polygon mesh whose
# metrics (re-measured from the file by `metrics`) agree with the remesh report; the written parameterization
# re-measures to the same ARAP; --vertices controls the density; bad input gives exit 2 and no output file.
set -euo pipefail
cd "$(dirname "$0")/../.."
BIN=${QUADCOVER_BIN:-build/quadcover}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

for mesh in bunny_3k torus_5k lilium_disk; do
  "$BIN" remesh "tests/data/$mesh.obj" -o "$OUT/$mesh.quad.obj" --vertices 1500 --report "$OUT/$mesh.json" \
    --param "$OUT/$mesh.param.obj" --json -q >"$OUT/$mesh.summary.json"
  "$BIN" metrics "$OUT/$mesh.quad.obj" --ref "tests/data/$mesh.obj" --json >"$OUT/$mesh.quadmetrics.json"
  "$BIN" metrics "$OUT/$mesh.param.obj" --json >"$OUT/$mesh.parammetrics.json"
  python3 - "$OUT" "$mesh" <<'PY'
import json, sys, os
out, mesh = sys.argv[1], sys.argv[2]
rep = json.load(open(f"{out}/{mesh}.json"))
qm = json.load(open(f"{out}/{mesh}.quadmetrics.json"))
pm = json.load(open(f"{out}/{mesh}.parammetrics.json"))
for key in ("input", "parameterization", "extraction", "quad_mesh", "surface_distance", "seconds"):
    assert key in rep, f"{mesh}: report lacks {key}"
q, q2 = rep["quad_mesh"], qm["quad_mesh"]
assert q["manifold"] and q2["manifold"], f"{mesh}: not manifold"
assert q["faces"] == q2["faces"] and q["vertices"] == q2["vertices"], f"{mesh}: file differs from report"
for k in ("rsd_edge_length", "rsd_corner_angle"):
    assert abs(q[k] - q2[k]) < 1e-6 * max(1, q[k]), f"{mesh}: {k} {q[k]} vs {q2[k]}"
assert 0.5 * 1500 < q["vertices"] < 1.5 * 1500, f"{mesh}: {q['vertices']} vertices for --vertices 1500"
assert rep["extraction"]["failed_traces"] == 0, mesh
assert qm["surface_distance"]["max"] < 0.05, f"{mesh}: far from the input {qm['surface_distance']}"
a, a2 = rep["parameterization"]["arap"], pm["parameterization"]["arap"]
assert abs(a - a2) < 1e-6 * max(1.0, a), f"{mesh}: ARAP {a} vs re-measured {a2}"
if mesh != "lilium_disk":
    assert q["closed"] or rep["extraction"]["flipped_triangles"] + rep["extraction"]["degenerate_triangles"] > 0, mesh
print(f"  {mesh}: {q['vertices']} vertices, {q['non_quads']} non-quads, RSD {q['rsd_edge_length']:.1f}% / "
      f"{q['rsd_corner_angle']:.1f}%, ARAP {a:.4f}")
PY
done

# bad input: exit 2, no output file
set +e
"$BIN" remesh tests/data/bad/$(ls tests/data/bad | grep -m1 '\.obj$') -o "$OUT/bad.obj" -q 2>/dev/null
rc=$?
set -e
[ "$rc" = 2 ] || { echo "remesh on a broken file: exit $rc, expected 2"; exit 1; }
[ ! -e "$OUT/bad.obj" ] || { echo "remesh left an output file for a broken input"; exit 1; }
set +e
"$BIN" remesh tests/data/bunny_3k.obj -o "$OUT/x.obj" --vertices 100 --edge-length 0.1 -q 2>/dev/null
rc=$?
set -e
[ "$rc" = 2 ] || { echo "--vertices with --edge-length: exit $rc, expected 2"; exit 1; }
echo "remesh/metrics CLI: ok"
