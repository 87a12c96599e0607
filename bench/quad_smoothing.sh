#!/usr/bin/env bash
# Quad smoothing before / after on every shipped mesh (tests/data/*.obj): `quadcover remesh` with its defaults, once
# with --smooth-quads 0 and once with the default 20 rounds; prints the Markdown table of BENCHMARKS.md
# ("Quad smoothing"). Usage: bench/quad_smoothing.sh [BIN]   (default build/quadcover)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build/quadcover}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for m in tests/data/*.obj; do
  name=$(basename "$m" .obj)
  "$BIN" remesh "$m" -o "$tmp/$name.0.obj" --smooth-quads 0 --report "$tmp/$name.0.json" -q
  "$BIN" remesh "$m" -o "$tmp/$name.20.obj" --report "$tmp/$name.20.json" -q
done
/usr/bin/python3 - "$tmp" <<'PY'
import json, pathlib, sys
d = pathlib.Path(sys.argv[1])
print("| mesh | quads | RSD edge raw → smoothed | RSD angle raw → smoothed | max distance / diag raw → smoothed "
      "| fixed / rejected | mean / max displacement (h) | seconds |")
print("|---|---|---|---|---|---|---|---|")
tot = [0, 0, 0, 0, 0]
for raw in sorted(d.glob("*.0.json")):
    name = raw.name[:-len(".0.json")]
    a, b = json.loads(raw.read_text()), json.loads((d / f"{name}.20.json").read_text())
    qa, qb, s = a["quad_mesh"], b["quad_mesh"], b["quad_smoothing"]
    better = (qb["rsd_edge_length"] < qa["rsd_edge_length"]) + (qb["rsd_corner_angle"] < qa["rsd_corner_angle"])
    tot[0] += 1; tot[1] += qb["rsd_edge_length"] < qa["rsd_edge_length"]; tot[2] += qb["rsd_corner_angle"] < qa["rsd_corner_angle"]
    tot[3] += qa["rsd_edge_length"] - qb["rsd_edge_length"]; tot[4] += qa["rsd_corner_angle"] - qb["rsd_corner_angle"]
    print(f"| {name} | {qb['quads']} | {qa['rsd_edge_length']:.1f} → {qb['rsd_edge_length']:.1f} % "
          f"| {qa['rsd_corner_angle']:.1f} → {qb['rsd_corner_angle']:.1f} % "
          f"| {a['surface_distance']['max']:.4f} → {b['surface_distance']['max']:.4f} "
          f"| {s['fixed_vertices']} / {s['rejected_moves']} | {s['mean_displacement']:.3f} / {s['max_displacement']:.2f} "
          f"| {b['seconds']['smooth']:.3f} |")
print(f"\nRSD edge lower on {tot[1]} of {tot[0]} meshes (mean −{tot[3]/tot[0]:.1f} points), "
      f"RSD angle lower on {tot[2]} of {tot[0]} (mean −{tot[4]/tot[0]:.1f} points).")
PY
