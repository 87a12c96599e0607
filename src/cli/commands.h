#pragma once
// Each subcommand registers itself on the CLI11 app; main() only dispatches and maps errors to exit codes.
#include <CLI/CLI.hpp>

namespace quadcover::cli {

/// Options every subcommand shares.
struct GlobalOptions {
  bool json = false;
  bool quiet = false;
  bool verbose = false;
};

/// Exit codes: 0 success, 1 internal/numerical failure, 2 bad input or usage.
enum ExitCode { kOk = 0, kInternal = 1, kBadInput = 2 };

}  // namespace quadcover::cli
