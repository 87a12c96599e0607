#!/usr/bin/env bash
# `pip install .` in a fresh virtual environment (python3 -m venv --system-site-packages, offline: Debian's
# setuptools as the build backend, --no-build-isolation --no-index), reusing the CMake build in build/ through
# QUADCOVER_BUILD_DIR. Then, from outside the repository and without PYTHONPATH: the installed package imports from
# the venv, `python -m quadcover` and the `quadcover` script run the bundled CLI, and the package tests pass.
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT=$PWD
PY=/usr/bin/python3
"$PY" -c "import ensurepip, setuptools, wheel" 2>/dev/null ||
  { echo "34_pip: $PY needs python3-venv, python3-setuptools and python3-wheel (scripts/setup.sh)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# --without-pip: the venv runs Debian's pip from the system site-packages (ensurepip would take ~15 s).
"$PY" -m venv --system-site-packages --without-pip "$work/venv"
VPY="$work/venv/bin/python"
t0=$SECONDS
QUADCOVER_BUILD_DIR="${QUADCOVER_BUILD_DIR:-$ROOT/build}" "$VPY" -m pip install -q --no-build-isolation --no-index .
echo "34_pip: pip install took $((SECONDS - t0)) s"
cd "$work"
unset PYTHONPATH
"$VPY" - "$work/venv" <<'PY'
import os, sys
import quadcover
venv = os.path.realpath(sys.argv[1])
assert os.path.realpath(quadcover.__file__).startswith(venv), quadcover.__file__
assert os.path.realpath(quadcover.cli_path()).startswith(venv), quadcover.cli_path()
print("34_pip: quadcover", quadcover.__version__, "from", os.path.dirname(quadcover.__file__))
PY
"$VPY" -m quadcover --version
"$VPY" -m quadcover remesh "$ROOT/tests/data/torus_5k.obj" -o "$work/torus.quad.obj" -q
"$work/venv/bin/quadcover" metrics "$work/torus.quad.obj" -q  # the console script runs the same CLI
test -s "$work/torus.quad.obj"
set +e
"$VPY" -m quadcover remesh "$work/missing.obj" -q 2>/dev/null
code=$?
set -e
[ "$code" -eq 2 ] || { echo "34_pip: a missing input should exit 2, got $code"; exit 1; }
# The package's own tests (read/write, mesh-like objects, faces=, progress=, python -m quadcover) on the install.
"$VPY" -m pytest -q -p no:cacheprovider --rootdir "$work" "$ROOT/python/tests/test_package.py"
