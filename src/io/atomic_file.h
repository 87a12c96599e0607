#pragma once
// Atomic output: write to a temporary file next to the target, then rename over it. A failure (exception,
// cancelled run, a signal handled by remove_temporary_files()) leaves no partial file behind.
#include <fstream>
#include <functional>
#include <string>

namespace quadcover {

/// Calls `write(stream)` on a temporary file in the target's directory and renames it to `path` on success.
/// `path` "-" means standard output: the bytes are collected in memory and written to stdout only on success.
/// The output guard (set_output_guard) is asked first.
/// \throw InputError (naming `path`) if the file cannot be created, written or renamed; the temporary is removed.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// A check run by write_file_atomically before anything is created (e.g. the CLI refuses to replace an input
/// file); it throws to refuse. An empty function (the default) accepts every path.
using OutputGuard = std::function<void(const std::string& path)>;
void set_output_guard(OutputGuard guard);  ///< \pre none
/// Runs the output guard on `path` now (e.g. when an output name is chosen, before the work). \throw as the guard.
void check_output_guard(const std::string& path);

/// Removes every temporary file an unfinished write_file_atomically has created. Async-signal-safe (only unlink
/// on a fixed table): for a signal handler that then exits. \pre none
void remove_temporary_files() noexcept;

/// True once write_file_atomically has written to standard output ("-"). \pre none
bool wrote_standard_output();

}  // namespace quadcover
