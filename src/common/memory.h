#pragma once
// Resident memory of this process, for per-stage peaks in reports and benchmarks (Linux /proc/self; 0 elsewhere).
#include <cstdint>
#include <fstream>
#include <string>

/// Defined when this build allocates with glibc's malloc (no sanitizer replaces it): its tunables, mallopt and
/// malloc_info apply.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define QUADCOVER_GLIBC_MALLOC 1
#endif

namespace quadcover {

namespace detail {
/// The value in kB of a "Name:   123 kB" line of /proc/self/status, in bytes; 0 if absent.
inline std::int64_t proc_status_bytes(const char* name) {
  std::ifstream in("/proc/self/status");
  std::string key;
  std::int64_t kb = 0;
  while (in >> key) {
    if (key == name) {
      in >> kb;
      return kb * 1024;
    }
    in.ignore(1 << 12, '\n');
  }
  return 0;
}
}  // namespace detail

/// Current resident set size (VmRSS) in bytes; 0 if unknown. \pre none
inline std::int64_t resident_bytes() { return detail::proc_status_bytes("VmRSS:"); }

/// Peak resident set size (VmHWM) since process start or since the last reset_peak_resident(), in bytes; 0 if
/// unknown. \pre none
inline std::int64_t peak_resident_bytes() { return detail::proc_status_bytes("VmHWM:"); }

/// Resets the peak to the current resident size (writes "5" to /proc/self/clear_refs, Linux ≥ 4.0), so that
/// peak_resident_bytes() after a stage is that stage's peak. The peak it clears is kept for every open
/// StagePeakMemory and for process_peak_resident_bytes(); the kernel's own maximum (getrusage ru_maxrss,
/// `/usr/bin/time -v`) is lowered with VmHWM, so a process that resets reports its peak itself. \return false if the
/// kernel refused (the peak then stays the process-wide one). \pre none
bool reset_peak_resident();

/// Whether this process's malloc asks the kernel for huge pages: glibc with the tunable glibc.malloc.hugetlb=1
/// (transparent huge pages) or 2 (hugetlbfs) in GLIBC_TUNABLES, no sanitizer (read at start-up; the CLI sets 1,
/// cli/huge_pages.h).
/// \pre none
bool malloc_asks_for_huge_pages();

/// Peak resident bytes since the process started, across resets; 0 if unknown. \pre none
std::int64_t process_peak_resident_bytes();

/// Peak resident bytes of one stage: construct before the stage (resets the peak), read peak() after it. The peak
/// is the process's: it includes what earlier stages left resident, and the heap they freed that malloc kept (giving
/// it back at every stage, malloc_trim, cost a fifth of the time on 10⁴-10⁵ faces in page faults; BENCHMARKS.md,
/// "One heap arena"). Stages may nest or run in parallel threads: a reset by one keeps the peak so far for all others,
/// so each sees the process's peak over its own interval (parallel ones therefore include each other's memory).
class StagePeakMemory {
 public:
  StagePeakMemory();
  ~StagePeakMemory();
  StagePeakMemory(const StagePeakMemory&) = delete;
  StagePeakMemory& operator=(const StagePeakMemory&) = delete;

  /// The stage's peak in bytes so far (the process peak so far if the reset failed, see reset_ok()). \pre none
  std::int64_t peak() const;
  /// Starts a new stage here: resets the peak (keeping it for the other open stages) and forgets this one's. \pre none
  void restart();
  bool reset_ok() const { return reset_; }  ///< \pre none

 private:
  friend struct OpenStages;
  bool reset_ = false;
  std::int64_t kept_ = 0;  ///< the largest peak cleared by resets since this stage began
};

}  // namespace quadcover
