#!/usr/bin/env bash
# Set-up, build, and the main job on a mesh shipped in the repository.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
./build/quadcover info tests/data/bunny_3k.obj
