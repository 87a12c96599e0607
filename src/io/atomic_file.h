#pragma once
// Atomic output: write to a temporary file next to the target, then rename over it. A failure (exception,
// cancelled run) leaves no partial file behind.
#include <fstream>
#include <functional>
#include <string>

namespace quadcover {

/// Calls `write(stream)` on a temporary file in the target's directory and renames it to `path` on success.
/// \throw InputError (naming `path`) if the file cannot be created, written or renamed; the temporary is removed.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace quadcover
