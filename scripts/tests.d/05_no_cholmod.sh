#!/usr/bin/env bash
# The Eigen fallback of SparseCholesky (no CHOLMOD): configure build-nocholmod with QUADCOVER_USE_CHOLMOD=OFF,
# build only the calculus tests and run them, so the non-GPL build path stays correct. Its test files compile one
# by one (QUADCOVER_UNITY_TESTS=OFF), so that build stays checked too.
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake -S . -B build-nocholmod -G Ninja -DCMAKE_BUILD_TYPE=Release -DQUADCOVER_USE_CHOLMOD=OFF \
  -DQUADCOVER_BUILD_BENCH=OFF -DQUADCOVER_UNITY_TESTS=OFF >/dev/null
cmake --build build-nocholmod --target test_calculus -j"$(nproc)"
./build-nocholmod/tests/test_calculus --gtest_brief=1
