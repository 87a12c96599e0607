#!/usr/bin/env bash
# Reproduces html/vendor/three.module.min.js (three.js, MIT licence) from the npm registry with npm only.
# The HTML report embeds this file so pages open from disk with no network. Pinned version: change THREE_VERSION
# and re-run to upgrade (three r160 is the last release whose ES module build is a single file).
set -euo pipefail
cd "$(dirname "$0")"
THREE_VERSION=${THREE_VERSION:-0.160.1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack --silent "three@${THREE_VERSION}" >/dev/null && tar xzf three-*.tgz)
mkdir -p vendor
cp "$work/package/build/three.module.min.js" vendor/three.module.min.js
cp "$work/package/LICENSE" vendor/LICENSE-three.txt
echo "three@${THREE_VERSION}" > vendor/VERSION-three.txt
if grep -q '</script' vendor/three.module.min.js; then
  echo "update_three.sh: the module contains '</script' and cannot be inlined" >&2
  exit 1
fi
echo "html/vendor: three@${THREE_VERSION} ($(wc -c < vendor/three.module.min.js) bytes)"
