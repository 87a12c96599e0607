#!/usr/bin/env bash
# Set-up, build, and the whole test suite: ctest on the Release build, then every scripts/tests.d/*.sh in order
# (sanitizer build, Python module, fuzzers, end-to-end checks). Prints "N passed, N failed" at the end.
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh || exit 1
passed=0; failed=0; failures=(); timings=("$(printf '%5ds  %s' "$SECONDS" "setup.sh (packages + Release build)")")
run_step() {
  local name=$1; shift
  echo "=== $name"
  local t0=$SECONDS
  if "$@"; then passed=$((passed + 1)); else failed=$((failed + 1)); failures+=("$name"); fi
  timings+=("$(printf '%5ds  %s' $((SECONDS - t0)) "$name")")
}
run_step "ctest (Release)" ctest --test-dir build --output-on-failure -j"$(nproc)"
for step in scripts/tests.d/*.sh; do
  [ -e "$step" ] || continue
  run_step "$(basename "$step" .sh)" bash "$step"
done
echo "=== step times (load average: $(cut -d' ' -f1-3 /proc/loadavg))"; printf '%s\n' "${timings[@]}"
((failed)) && echo "failed steps: ${failures[*]}"
echo "test steps: $passed passed, $failed failed"
((failed == 0))
