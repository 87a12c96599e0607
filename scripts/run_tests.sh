#!/usr/bin/env bash
# Set-up, build, and the whole test suite: ctest on the Release build, then every scripts/tests.d/*.sh in order
# (sanitizer build, Python module, fuzzers, end-to-end checks). Prints "N passed, N failed" at the end.
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh || exit 1
passed=0; failed=0; failures=()
run_step() {
  local name=$1; shift
  echo "=== $name"
  if "$@"; then passed=$((passed + 1)); else failed=$((failed + 1)); failures+=("$name"); fi
}
run_step "ctest (Release)" ctest --test-dir build --output-on-failure -j"$(nproc)"
for step in scripts/tests.d/*.sh; do
  [ -e "$step" ] || continue
  run_step "$(basename "$step" .sh)" bash "$step"
done
((failed)) && echo "failed steps: ${failures[*]}"
echo "test steps: $passed passed, $failed failed"
((failed == 0))
