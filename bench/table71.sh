#!/usr/bin/env bash
# Reproduces thesis Table 7.1 (bunny at ~6500 output vertices) with bench_table71 and writes the result into the
# "## Table 7.1" section of BENCHMARKS.md (replacing that section only).
# Usage: bench/table71.sh [BUILD_DIR]   (default: build; needs -DQUADCOVER_BUILD_BENCH=ON)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bin="$build/bench/bench_table71"
[ -x "$bin" ] || { echo "missing $bin: cmake --build $build --target bench_table71" >&2; exit 1; }
table=$("$bin" --table)
cpu=$(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')
section=$(cat <<MD
## Table 7.1

Thesis Table 7.1 reproduced on \`tests/data/bunny_3k.obj\` (closed Stanford bunny, 3k faces) at about 6500 output
vertices: frame field (ch. 5) → [optimization of the matching, ch. 6] → QuadCover parameterization (ch. 2-4, rotated
lattice, period rounding 6.3) → quad extraction (\`src/quad\`). Made by \`bench/table71.sh BUILD\` (BUILD a Release
build with \`-DQUADCOVER_BUILD_BENCH=ON\` and target \`bench_table71\`, which prints the table with \`--table\`; about
35 s) on $(date -u +%Y-%m-%d), $cpu, $(nproc) cores shared with other jobs, commit $(git rev-parse --short HEAD).

Columns (\`bench/table71_bench.cpp\`; each density calibrated once so that the output has about 6500 vertices):
- **QuadCover**: plain [KNP07], no optimization, direct rounding of the periods (\`--optimize none --rounding direct\`).
- **Relocation**: Algorithm 6.1 without creation of branch points (cancellation + sorted curl reduction, until
  converged) and the r = 3 rounding search (\`--optimize relocate --rounding search3 --max-iterations 0\`; the CLI
  default, whose 3000-evaluation budget is not reached here).
- **Balancing (full)**: Algorithm 6.1 with creation, then balancing (6.4) until no cancellation pays, r = 3 rounding
  (\`--optimize full --max-iterations 0\`).
- **full, CLI budget 3000**: as the previous one but stopped after 3000 E_D evaluations (\`--optimize full\`).

$table

Definitions (\`src/metrics\`): RSD = standard deviation / mean, in percent, over the undirected edges (edge length)
and over all face corners (angle) of the quad mesh. **ARAP**: scale the map globally so that its total UV area
equals the 3D area, then ARAP = ½ × area-weighted mean over triangles of min over rotations ‖J − R‖²_F (J the
Jacobian of the scaled map). The thesis's ARAP column (0.50 / 0.36 / 0.33) does not state its normalization and is
not comparable. "branch points" are cones of the map (parameter angle sum ≠ 2π); "field branch points" are the
singular vertices of the cross field before and after Algorithm 6.1; irregular vertices are interior quad vertices of
valence ≠ 4. Peer reference (issue 7): libigl MIQ + QEx on this mesh reaches RSD edge 9.2 %, RSD angle 7.0 %, 34
irregular vertices, ARAP 0.0123, 0 flips, in 0.4 s.

Reading the table (the row "issue-7 goals missed" lists the goals each column misses):
- Our plain QuadCover is more regular than the thesis's (RSD 15 % / 12 % against 18.2 % / 14.8 %): the smooth power
  field fill (BENCHMARKS.md, "Frame field") starts from fewer misplaced branch points.
- Relocation lowers the map's E_D by about 10 %, RSD and ARAP by 5-15 %, and removes 8 of the 42 field branch points,
  keeping the quad mesh closed, all-quad and with the fewest irregular vertices; it is the CLI default for that
  reason. The thesis's Relocation column has 59 branch points against its 37, so it apparently allowed creation;
  ours moves and cancels only (Figures 6.7c / 6.8c).
- Creation and balancing (6.4, Δ_ED and Δ_EH compared in the same units) reach the thesis's branch point count
  (88 field branch points against its 93) and lower RSD angle, ARAP and the map's E_D further, at the price of more
  irregular vertices, a few non-quads and ~50 × the time when run to convergence. Stopping after the CLI's 3000
  evaluations (balancing keeps a third of them) gives the lowest RSD and ARAP of all columns in a few seconds, with
  about twice relocation's irregular vertices.
- All columns stay far from the thesis's 8.1 % / 7.2 % and from MIQ's 9.2 % / 7.0 %, ARAP 0.0123: the map keeps a
  large curl part (E_D 1.5-3.5 × E_H), and every column has a few flipped triangles.
MD
)
python3 - "$section" <<'PY'
import re, sys, pathlib
path = pathlib.Path("BENCHMARKS.md")
text = path.read_text() if path.exists() else "# Benchmarks\n"
section = sys.argv[1].rstrip() + "\n"
m = re.search(r"^## Table 7\.1\n.*?(?=^## |\Z)", text, flags=re.S | re.M)
if m:
    text = text[:m.start()] + section + ("\n" if m.end() < len(text) else "") + text[m.end():]
else:
    text = text.rstrip() + "\n\n" + section
path.write_text(text)
PY
echo "updated BENCHMARKS.md (section Table 7.1)"
