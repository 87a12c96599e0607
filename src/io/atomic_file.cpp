#include "io/atomic_file.h"

#include <cstdio>
#include <filesystem>
#include <system_error>
#include <unistd.h>

#include "common/errors.h"

namespace quadcover {

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const fs::path tmp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()));
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
