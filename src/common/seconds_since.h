#pragma once
// Wall seconds since a time point of the steady clock, for the timings the reports give.
#include <chrono>

namespace quadcover {

using SteadyClock = std::chrono::steady_clock;

/// Seconds from t0 to now. \pre none
inline double seconds_since(SteadyClock::time_point t0) {
  return std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

}  // namespace quadcover
