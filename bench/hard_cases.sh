#!/usr/bin/env bash
# Runs `quadcover param` and `quadcover remesh` on the generated hard-case meshes of bench/hard_cases.py and prints
# a Markdown table from bench/check_outputs.py, which reads only the written OBJ files: flipped/collapsed map
# triangles, quad mesh faces, non-quads and topology against the input's, exit codes and wall times.
# Usage: bench/hard_cases.sh [BUILD_DIR] [OUTDIR]   (default: build, and a temporary folder removed at exit)
# Exits 0 whatever quadcover does (a failing case is a row of the table); 1 when the generator or checker fails.
# HARD_CASES_TIMEOUT (seconds, default 1200) bounds each quadcover command (exit 124 = timed out).
# HARD_CASES_ARGS (default empty) is added to both commands, e.g. "--faces 200" for coarse maps with close cones.
set -uo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=$(realpath -m "${1:-$repo/build}")
bin="$build/quadcover"
py=/usr/bin/python3
limit=${HARD_CASES_TIMEOUT:-1200}
read -r -a extra <<<"${HARD_CASES_ARGS:-}"
if [ $# -ge 2 ]; then
  out=$(realpath -m "$2")
  mkdir -p "$out" || exit 1
else
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
[ -x "$bin" ] || { echo "missing $bin" >&2; exit 1; }

# seconds since the epoch with microseconds
now() { echo "$EPOCHREALTIME"; }

# run NAME KIND ARGS...: runs the command with stderr to NAME.KIND.err; prints "exit seconds stderr_lines"
run() {
  local name=$1 kind=$2 t0 rc
  shift 2
  t0=$(now)
  timeout "$limit" "$@" 2>"$out/$name.$kind.err" >/dev/null
  rc=$?
  awk -v a="$t0" -v b="$(now)" -v rc="$rc" -v n="$(wc -l <"$out/$name.$kind.err")" \
    'BEGIN { printf "%d %.2f %d", rc, b - a, n }'
}

echo "## Hard cases"
echo
echo '```'
echo "$py $repo/bench/hard_cases.py $out"
echo "$bin param $out/M.obj -o $out/M.param.obj -q --report $out/M.param.json ${extra[*]}"
echo "$bin remesh $out/M.obj -o $out/M.quads.obj -q --report $out/M.quads.json ${extra[*]}"
echo "$py $repo/bench/check_outputs.py $out $out/runs.tsv"
echo '```'
echo
start=$(now)
"$py" "$repo/bench/hard_cases.py" "$out" >"$out/generate.log" 2>&1 || {
  cat "$out/generate.log" >&2
  echo "hard_cases.py failed" >&2
  exit 1
}
echo '```'
cat "$out/generate.log"
echo '```'
echo
: >"$out/runs.tsv"
for mesh in "$out"/*.obj; do
  name=$(basename "$mesh" .obj)
  case $name in *.param | *.quads) continue ;; esac
  rm -f "$out/$name".{param,quads}.{obj,json} # no stale outputs from an earlier run
  p=$(run "$name" param "$bin" param "$mesh" -o "$out/$name.param.obj" -q --report "$out/$name.param.json" "${extra[@]}")
  r=$(run "$name" remesh "$bin" remesh "$mesh" -o "$out/$name.quads.obj" -q --report "$out/$name.quads.json" "${extra[@]}")
  echo "$name $p $r" >>"$out/runs.tsv"
  echo "$name: param $p, remesh $r (exit seconds stderr-lines)" >&2
done
"$py" "$repo/bench/check_outputs.py" "$out" "$out/runs.tsv" || { echo "check_outputs.py failed" >&2; exit 1; }
awk -v a="$start" -v b="$(now)" 'BEGIN { printf "\ntotal: %.1f s (generation, runs and check)\n", b - a }'
exit 0
