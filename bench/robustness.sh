#!/usr/bin/env bash
# Time and peak memory of the CLI on a large generated mesh (issue 8: "a 1M-face mesh, memory and time reported"),
# one command at a time (info, field, param, remesh) with GNU time. Prints a Markdown table for the "## Robustness"
# section of BENCHMARKS.md.
# Usage: bench/robustness.sh [BUILD_DIR] [FACES]   (default: build, 1000000; needs the quadcover binary)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
faces=${2:-1000000}
bin="$build/quadcover"
[ -x "$bin" ] || { echo "missing $bin: cmake --build $build --target quadcover" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "needs GNU time (/usr/bin/time, Debian package 'time')" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# A bumpy torus with 2·n·m ≈ FACES triangles (n = 2m): curvature varies everywhere, so the field, the cut graph
# (genus 1) and the branch points are those of a real surface, not of a flat grid.
/usr/bin/python3 - "$work/big.obj" "$faces" <<'PY'
import math, sys
path, faces = sys.argv[1], int(sys.argv[2])
m = max(4, int(round(math.sqrt(faces / 4))))
n = 2 * m
R, r = 2.0, 0.7
with open(path, "w") as f:
    for i in range(n):
        u = 2 * math.pi * i / n
        for j in range(m):
            v = 2 * math.pi * j / m
            rr = r * (1 + 0.08 * math.sin(5 * u) * math.cos(3 * v))
            f.write("v %.9g %.9g %.9g\n" % ((R + rr * math.cos(v)) * math.cos(u), (R + rr * math.cos(v)) * math.sin(u),
                                          rr * math.sin(v)))
    vid = lambda i, j: (i % n) * m + (j % m) + 1
    for i in range(n):
        for j in range(m):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            f.write("f %d %d %d\nf %d %d %d\n" % (a, b, c, a, c, d))
PY
nf=$(grep -c '^f ' "$work/big.obj")
nv=$(grep -c '^v ' "$work/big.obj")
echo "| command | faces | wall time (s) | peak memory (MB) | exit | result |"
echo "|---|---:|---:|---:|---:|---|"
for cmd in info field param remesh; do
  case $cmd in
    info) args=() ;;
    field) args=(-o "$work/big.field.json") ;;
    param) args=(-o "$work/big.param.obj") ;;
    remesh) args=(-o "$work/big.quad.obj") ;;
  esac
  set +e
  /usr/bin/time -f "%e %M" -o "$work/time.txt" "$bin" "$cmd" "$work/big.obj" "${args[@]}" --json -q \
    >"$work/out.json" 2>"$work/err.txt"
  rc=$?
  set -e
  read -r secs kb < <(tail -1 "$work/time.txt")
  summary=$(/usr/bin/python3 - "$work/out.json" "$cmd" <<'PY'
import json, sys
try:
    j = json.load(open(sys.argv[1]))
except Exception:
    print("-"); sys.exit()
keys = {"info": ["vertices", "genus"], "field": ["branch_points", "index_sum"],
        "param": ["branch_points", "flipped_triangles", "seamless"], "remesh": ["faces", "non_quads", "manifold"]}[sys.argv[2]]
print(", ".join("%s %s" % (k, j[k]) for k in keys if k in j))
PY
)
  [ "$rc" -eq 0 ] || summary="$(head -c 160 "$work/err.txt" | tr '\n' ' ')"
  echo "| $cmd | $nf | $secs | $((kb / 1024)) | $rc | $summary |"
done
echo
echo "Input: bumpy torus, $nv vertices, $nf faces ($(du -m "$work/big.obj" | cut -f1) MB OBJ); $(nproc) cores" \
  "($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')), load average $(cut -d' ' -f1 /proc/loadavg)."
