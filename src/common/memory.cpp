#include "common/memory.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <mutex>
#include <vector>

namespace quadcover {

/// The stages being measured, and the process peak cleared by resets: one reset serves them all.
struct OpenStages {
  std::mutex mutex;
  std::vector<StagePeakMemory*> stages;
  std::int64_t process_peak = 0;

  static OpenStages& get() {
    static OpenStages open;
    return open;
  }

  /// Keeps the current peak for every open stage and the process, then resets it. \pre mutex is held.
  bool keep_and_reset() {
    const std::int64_t peak = peak_resident_bytes();
    process_peak = std::max(process_peak, peak);
    for (StagePeakMemory* s : stages) s->kept_ = std::max(s->kept_, peak);
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return static_cast<bool>(out);
  }

  void open(StagePeakMemory& s) {
    std::lock_guard lock(mutex);
    s.reset_ = keep_and_reset();
    s.kept_ = 0;
    stages.push_back(&s);
  }

  void restart(StagePeakMemory& s) {
    std::lock_guard lock(mutex);
    s.reset_ = keep_and_reset();
    s.kept_ = 0;
  }

  void close(StagePeakMemory& s) {
    std::lock_guard lock(mutex);
    stages.erase(std::remove(stages.begin(), stages.end(), &s), stages.end());
  }

  /// Also kept as the process's: the kernel's counters behind VmHWM are approximate across CPUs (a later read may
  /// be a few pages lower), and the process peak reported must not be below a stage's.
  std::int64_t peak_of(const StagePeakMemory& s) {
    std::lock_guard lock(mutex);
    const std::int64_t peak = std::max(s.kept_, peak_resident_bytes());
    process_peak = std::max(process_peak, peak);
    return peak;
  }
};

bool reset_peak_resident() {
  OpenStages& open = OpenStages::get();
  std::lock_guard lock(open.mutex);
  return open.keep_and_reset();
}

std::int64_t process_peak_resident_bytes() {
  OpenStages& open = OpenStages::get();
  std::lock_guard lock(open.mutex);
  return std::max(open.process_peak, peak_resident_bytes());
}

bool malloc_asks_for_huge_pages() {
#ifdef QUADCOVER_GLIBC_MALLOC
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (!tunables) return false;
  const std::string t = tunables;
  const std::string key = "glibc.malloc.hugetlb=";
  for (std::size_t at = t.find(key); at != std::string::npos; at = t.find(key, at + 1))
    if ((at == 0 || t[at - 1] == ':') && at + key.size() < t.size() &&
        (t[at + key.size()] == '1' || t[at + key.size()] == '2'))
      return true;
#endif
  return false;
}

StagePeakMemory::StagePeakMemory() { OpenStages::get().open(*this); }
StagePeakMemory::~StagePeakMemory() { OpenStages::get().close(*this); }
std::int64_t StagePeakMemory::peak() const { return OpenStages::get().peak_of(*this); }
void StagePeakMemory::restart() { OpenStages::get().restart(*this); }

}  // namespace quadcover
