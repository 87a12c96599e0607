#!/usr/bin/env bash
# The Blender add-on (blender/quadcover_remesh) in Debian's blender 3.4 (installed here if missing), headless:
# sphere, torus and bunny to all-quad objects, loose parts, n-gons, Suzanne's report, Esc; then installed from a
# zip with the module folder in its preferences (tests/blender).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${QUADCOVER_PY_BUILD:-build}
if ! command -v blender >/dev/null 2>&1; then
  echo "36_blender: installing blender"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  if ! { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
         --no-install-recommends blender >/dev/null; }; then
    echo "36_blender: SKIPPED: blender cannot be installed here (apt-get failed)"; exit 0
  fi
fi
cmake --build "$BUILD" --target quadcover_python -j"${JOBS:-$(nproc)}" >/dev/null
users=$(mktemp -d)
trap 'rm -rf "$users"' EXIT
run() {  # Blender's own start/quit lines left out
  "$@" 2>&1 | grep -v -e '^$' -e '^Blender quit$' -e '^Read prefs' -e '^Blender 3' -e 'not disabled$'
  return "${PIPESTATUS[0]}"
}
run blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py -- "$PWD/$BUILD/python"
# Installed from a zip into an empty user folder, as a user does; the module found through the preference.
BLENDER_USER_SCRIPTS="$users" run blender -b --factory-startup --python-exit-code 1 \
  --python tests/blender/test_install.py -- "$PWD/$BUILD/python"
