#!/usr/bin/env bash
# Fuzzes every mesh reader (OBJ, OFF, PLY, STL) with libFuzzer + ASan + UBSan for a bounded time each, starting
# from the seed corpus of small real files in fuzz/corpus/<format>/. Builds with clang in build-fuzz/.
# Any crash, hang (> 10 s on one input), leak, sanitizer report or memory blow-up (> 2 GB) fails the step; the
# offending input is kept in build-fuzz/artifacts/ (rerun: build-fuzz/fuzz/fuzz_<fmt> <artifact>).
# FUZZ_SECONDS (default 15) sets the time per reader.
set -euo pipefail
cd "$(dirname "$0")/../.."
SECONDS_PER_READER=${FUZZ_SECONDS:-15}
BUILD=build-fuzz

if ! command -v clang++ >/dev/null; then
  echo "20_fuzz: clang++ not found (scripts/setup.sh installs it)" >&2
  exit 1
fi
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DQUADCOVER_FUZZ=ON -DQUADCOVER_SANITIZE=ON -DQUADCOVER_BUILD_TESTS=OFF -DQUADCOVER_BUILD_BENCH=OFF >/dev/null
cmake --build "$BUILD" -j"${JOBS:-$(nproc)}" --target fuzz_obj fuzz_off fuzz_ply fuzz_stl

mkdir -p "$BUILD/artifacts"
# One reader per core at a time (each fuzzer is single-threaded): the same time per reader, less wall time.
fuzz_reader() {
  local fmt=$1 work="$BUILD/corpus/$1"  # the fuzzer adds inputs here; the committed seeds stay untouched
  mkdir -p "$work"
  cp -n fuzz/corpus/"$fmt"/* "$work"/ 2>/dev/null || true
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$BUILD/fuzz/fuzz_$fmt" "$work" -max_total_time="$SECONDS_PER_READER" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -max_len=65536 -print_final_stats=1 -artifact_prefix="$BUILD/artifacts/${fmt}-" \
    >"$BUILD/fuzz_$fmt.log" 2>&1
}
declare -A pid
for fmt in obj off ply stl; do
  while (($(jobs -rp | wc -l) >= ${JOBS:-$(nproc)})); do wait -n || true; done
  fuzz_reader "$fmt" &
  pid[$fmt]=$!
done
status=0
for fmt in obj off ply stl; do
  echo "--- fuzz_$fmt: ${SECONDS_PER_READER}s"
  if ! wait "${pid[$fmt]}"; then
    echo "fuzz_$fmt FAILED (log: $BUILD/fuzz_$fmt.log)"
    grep -E "ERROR|SUMMARY|Test unit written|runtime error" "$BUILD/fuzz_$fmt.log" | head -20
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "$BUILD/fuzz_$fmt.log" | tail -2
  fi
done
exit $status
