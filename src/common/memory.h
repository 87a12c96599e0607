#pragma once
// Resident memory of this process, for per-stage peaks in reports and benchmarks (Linux /proc/self; 0 elsewhere).
#include <cstdint>
#include <fstream>
#include <string>

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

/// Current resident set size (VmRSS) in bytes; 0 if unknown.
inline std::int64_t resident_bytes() { return detail::proc_status_bytes("VmRSS:"); }

/// Peak resident set size (VmHWM) since process start or since the last reset_peak_resident(), in bytes; 0 if
/// unknown.
inline std::int64_t peak_resident_bytes() { return detail::proc_status_bytes("VmHWM:"); }

/// Resets the peak to the current resident size (writes "5" to /proc/self/clear_refs, Linux ≥ 4.0), so that
/// peak_resident_bytes() after a stage is that stage's peak. \return false if the kernel refused (the peak then
/// stays the process-wide one).
inline bool reset_peak_resident() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

/// Peak resident bytes of one stage: construct before the stage (resets the peak), read peak() after it.
class StagePeakMemory {
 public:
  StagePeakMemory() : reset_(reset_peak_resident()) {}
  /// The stage's peak in bytes (the process peak so far if the reset failed, see reset_ok()).
  std::int64_t peak() const { return peak_resident_bytes(); }
  bool reset_ok() const { return reset_; }

 private:
  bool reset_;
};

}  // namespace quadcover
