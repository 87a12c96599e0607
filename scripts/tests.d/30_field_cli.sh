#!/usr/bin/env bash
# `quadcover field` end to end: JSON report keys, Poincaré–Hopf (index_sum = χ) on closed meshes, the written
# FIELD.json (one frame per face, one matching per edge, 3D cross directions), options, and bad input (exit 2,
# no output file).
set -euo pipefail
cd "$(dirname "$0")/../.."
BIN=${QUADCOVER_BIN:-build/quadcover}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

check() {  # check MESH EXTRA_ARGS... : runs the command and validates report + file with python
  local mesh=$1; shift
  "$BIN" field "tests/data/$mesh.obj" -o "$OUT/$mesh.json" --json "$@" >"$OUT/$mesh.report.json"
  python3 - "$OUT/$mesh.report.json" "$OUT/$mesh.json" "$mesh" "$*" <<'PY'
import json, sys
report = json.load(open(sys.argv[1])); field = json.load(open(sys.argv[2])); mesh, args = sys.argv[3], sys.argv[4]
for key in ("branch_points", "index_sum", "euler_characteristic", "energy_smooth"):
    assert key in report, f"{mesh}: report lacks {key}"
nf, ne = field["faces"], field["edges"]
assert len(field["X"]) == nf and len(field["cross_u"]) == nf and len(field["cross_v"]) == nf, mesh
assert len(field["matching"]) == ne and len(field["edge_vertices"]) == ne, mesh
assert report["branch_points"] == len(field["branch_points"]), mesh
assert all(b["quarter_index"] % 4 != 0 for b in field["branch_points"]), mesh
for u, v in zip(field["cross_u"], field["cross_v"]):
    assert abs(sum(a * a for a in u) - 1) < 1e-9 and abs(sum(a * b for a, b in zip(u, v))) < 1e-9, mesh
if report["boundary_loops"] == 0:
    assert report["index_sum"] == report["euler_characteristic"], f"{mesh}: Poincaré–Hopf violated: {report}"
if "off" in args or "--no-features" in args:  # fandisk is closed: nothing left to align to
    assert report["constrained_faces"] == 0, mesh
if "--features" in args and args.split()[-1].endswith(".txt"):  # the file gives fandisk's edge 1-2 only
    assert report["constrained_faces"] == 2 and field["options"]["given_feature_edges"] == 1, (report, field["options"])
print(f"  {mesh} {args}: {report['branch_points']} branch points, index sum {report['index_sum']}, "
      f"E_S {report['energy_smooth']:.1f}")
PY
}

check bunny_3k
check torus_5k --method csm
check eight_genus2 --trusted 0.3 --lambda 0.9 --rounds 1
check fandisk --features 50
check camelhead_boundary --features off
check fandisk --feature-angle 50
check fandisk --no-features
printf '# one edge\n1 2\n' >"$OUT/edge.txt"
check fandisk --features "$OUT/edge.txt"
check bunny_3k --fill propagate
check spot --fill smooth --fill-alignment 100 --fill-unit-weight 0 --fill-iterations 0

# The default smooth fill leaves far fewer branch points than the thesis propagation (bunny_3k: 42 vs 77).
"$BIN" field tests/data/bunny_3k.obj -o "$OUT/p.json" --json --fill propagate >"$OUT/p.report.json"
"$BIN" field tests/data/bunny_3k.obj -o "$OUT/s.json" --json >"$OUT/s.report.json"
python3 - "$OUT/s.report.json" "$OUT/p.report.json" "$OUT/s.json" <<'PY'
import json, sys
s, p, doc = (json.load(open(f)) for f in sys.argv[1:4])
assert doc["options"]["fill"] == "smooth", doc["options"]
assert s["branch_points"] <= 48 and s["branch_points"] < 0.75 * p["branch_points"], (s, p)
print(f"  bunny_3k fill smooth {s['branch_points']} vs propagate {p['branch_points']} branch points")
PY

# Bad input: exit status 2, message on stderr, no output file.
for bad in tests/data/bad/beetle_nonmanifold_edges.obj tests/data/bad/spot_quads_nontriangle.obj; do
  set +e
  "$BIN" field "$bad" -o "$OUT/bad.json" 2>"$OUT/bad.err"
  rc=$?
  set -e
  [ "$rc" -eq 2 ] || { echo "expected exit 2 for $bad, got $rc"; exit 1; }
  [ ! -e "$OUT/bad.json" ] || { echo "partial output written for $bad"; exit 1; }
  [ -s "$OUT/bad.err" ] || { echo "no error message for $bad"; exit 1; }
done
set +e
"$BIN" field tests/data/bunny_3k.obj -o "$OUT/x.json" --method nope 2>/dev/null; rc=$?
set -e
[ "$rc" -eq 2 ] || { echo "expected exit 2 for --method nope, got $rc"; exit 1; }
set +e
"$BIN" field tests/data/bunny_3k.obj -o "$OUT/x.json" --fill nope 2>/dev/null; rc=$?
set -e
[ "$rc" -eq 2 ] || { echo "expected exit 2 for --fill nope, got $rc"; exit 1; }
echo "field CLI: ok"
