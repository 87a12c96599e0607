#include "io/atomic_file.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <sstream>
#include <system_error>

#include "common/errors.h"

namespace quadcover {

namespace {
// Unique per call, not only per process: threads of a batch writing next to each other (or, by mistake, to the same
// target) must never share a temporary file.
std::string temporary_suffix() {
  static std::atomic<unsigned long> counter{0};
  return ".tmp" + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
}

// The temporary files being written, in a fixed table a signal handler can read without locks: a slot's path is
// complete before its flag is set (release) and the flag is cleared before the slot is reused.
constexpr std::size_t kSlots = 256, kPathBytes = 4096;
struct TemporarySlot {
  std::atomic<int> state{0};  // 0 free, 1 being filled or emptied, 2 holds a live temporary
  char path[kPathBytes] = {};
};
std::array<TemporarySlot, kSlots> g_temporaries;

/// Registers `path` for removal by a signal handler; returns the slot (or -1 if the table is full or the path too
/// long: the file is then only removed by the normal error path).
int register_temporary(const std::string& path) {
  if (path.size() >= kPathBytes) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_temporaries[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_temporaries[i].path, path.c_str(), path.size() + 1);
    g_temporaries[i].state.store(2, std::memory_order_release);
    return static_cast<int>(i);
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0) g_temporaries[static_cast<std::size_t>(slot)].state.store(0, std::memory_order_release);
}

std::mutex g_guard_mutex;
OutputGuard g_guard;
std::atomic<bool> g_wrote_stdout{false};

void write_standard_output(const std::function<void(std::ostream&)>& write) {
  std::ostringstream buffer;
  write(buffer);
  const std::string bytes = std::move(buffer).str();
  std::cout.flush();
  if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0)
    throw InputError("-", 0, "cannot write to standard output");
  g_wrote_stdout = true;
}
}  // namespace

void set_output_guard(OutputGuard guard) {
  std::lock_guard lock(g_guard_mutex);
  g_guard = std::move(guard);
}

void check_output_guard(const std::string& path) {
  OutputGuard guard;
  {
    std::lock_guard lock(g_guard_mutex);
    guard = g_guard;
  }
  if (guard) guard(path);
}

bool wrote_standard_output() { return g_wrote_stdout.load(); }

void remove_temporary_files() noexcept {
  for (auto& slot : g_temporaries)
    if (slot.state.load(std::memory_order_acquire) == 2) ::unlink(slot.path);
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  check_output_guard(path);
  if (path == "-") return write_standard_output(write);
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  fs::path tmp = dir / ".";  // then ".NAME<suffix>" beside the target
  tmp += target.filename();
  tmp += temporary_suffix();
  const int slot = register_temporary(tmp.string());  // before the file exists: a signal never misses it
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
    unregister_temporary(slot);
    throw;
  }
  unregister_temporary(slot);
}

}  // namespace quadcover
