#pragma once
// Reports of two runs of one job agree but for their costs: every "seconds" and "memory" key, at any depth (the
// stage timings, the optimizer's, each validity attempt's). The e2e suite strips the same keys (tests/e2e/e2e.py).
#include <nlohmann/json.hpp>

namespace quadcover::testing {

/// `report` without its "seconds" and "memory" keys at every depth. \pre none
inline nlohmann::json without_costs(nlohmann::json report) {
  if (report.is_object()) {
    report.erase("seconds");
    report.erase("memory");
    for (auto& [key, value] : report.items()) value = without_costs(std::move(value));
  } else if (report.is_array()) {
    for (auto& value : report) value = without_costs(std::move(value));
  }
  return report;
}

}  // namespace quadcover::testing
