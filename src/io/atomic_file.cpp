#include "io/atomic_file.h"

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <unistd.h>

#include "common/errors.h"

namespace quadcover {

namespace {
// Unique per call, not only per process: threads of a batch writing next to each other (or, by mistake, to the same
// target) must never share a temporary file.
std::string temporary_suffix() {
  static std::atomic<unsigned long> counter{0};
  return ".tmp" + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
}
}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const fs::path tmp = dir / ("." + target.filename().string() + temporary_suffix());
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw InputError(path, 0, "cannot create output file");
      write(out);
      out.flush();
      if (!out) throw InputError(path, 0, "write error");
    }
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) throw InputError(path, 0, "cannot move output into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

}  // namespace quadcover
