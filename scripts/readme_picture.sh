#!/usr/bin/env bash
# Re-makes the README picture html/images/bunny_pipeline.png from the repo's own output: tests/data/bunny_3k.obj through
# `param --png`, `remesh --png` and `render --uv-layout` with default settings, side by side (needs ImageMagick's
# `convert`: apt-get install imagemagick; not part of the build or the tests).
# Usage: bash scripts/readme_picture.sh [BIN]   (default build/quadcover)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build/quadcover}
MESH=tests/data/bunny_3k.obj
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$BIN" param "$MESH" -o "$tmp/p.obj" --png "$tmp/param.png" --size 414x400 -q
"$BIN" remesh "$MESH" -o "$tmp/q.obj" --png "$tmp/quads.png" --size 413x400 -q
"$BIN" render "$tmp/p.obj" -o "$tmp/uv.png" --uv-layout --size 413x400 -q
convert "$tmp/param.png" "$tmp/quads.png" "$tmp/uv.png" +append -strip html/images/bunny_pipeline.png
echo "wrote html/images/bunny_pipeline.png"
