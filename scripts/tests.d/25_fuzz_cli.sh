#!/usr/bin/env bash
# The command line under random options and corrupted inputs for a bounded time with a fixed seed
# (tests/cli/fuzz_cli.py): no crash, exit code in {0,1,2,3}, no output left on a non-zero exit, no temporary file,
# inputs byte-identical. FUZZ_CLI_SECONDS (default 40) and FUZZ_CLI_SEED (default 18) set the budget and the seed.
set -euo pipefail
cd "$(dirname "$0")/../.."
exec python3 tests/cli/fuzz_cli.py "${QUADCOVER_BIN:-build/quadcover}"
