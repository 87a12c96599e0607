#pragma once
// The cost of consecutive stages of a job: wall-clock seconds and peak resident bytes, measured at the same points
// under the same names (the report's "seconds" and "memory").
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/memory.h"

namespace quadcover {

/// Wall-clock seconds per stage, in pipeline order.
using StageSeconds = std::vector<std::pair<std::string, double>>;
/// Peak resident bytes per stage (common/memory.h StagePeakMemory), in pipeline order.
using StagePeakBytes = std::vector<std::pair<std::string, std::int64_t>>;

/// What one stage cost.
struct StageCost {
  double seconds = 0;
  std::int64_t peak_bytes = 0;
};

/// Measures stages one after the other: each lap() ends the stage begun at the last lap (or at construction or
/// restart()) and begins the next.
class StageMeter {
 public:
  using Clock = std::chrono::steady_clock;

  StageMeter() : start_(Clock::now()) {}

  /// \pre none
  StageCost lap() {
    const Clock::time_point now = Clock::now();
    const StageCost cost{std::chrono::duration<double>(now - start_).count(), memory_.peak()};
    start_ = now;
    memory_.restart();
    return cost;
  }

  /// lap(), appended to `seconds` and `peaks` under `stage`. \pre none
  StageCost lap(const std::string& stage, StageSeconds& seconds, StagePeakBytes& peaks) {
    const StageCost cost = lap();
    seconds.emplace_back(stage, cost.seconds);
    peaks.emplace_back(stage, cost.peak_bytes);
    return cost;
  }

  /// Begins the next stage here; the time and memory since the last lap are not recorded. \pre none
  void restart() {
    start_ = Clock::now();
    memory_.restart();
  }

 private:
  Clock::time_point start_;
  StagePeakMemory memory_;
};

}  // namespace quadcover
