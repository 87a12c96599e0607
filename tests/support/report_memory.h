#pragma once
// Checks of a job report's "memory" section (src/pipeline/job_report.h) shared by the library and CLI tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace quadcover::testing {

/// The memory section has one entry per stage of "seconds" (the same names, each once), a positive peak per stage on
/// Linux, bytes per face that are the peak over the input's faces, and a process peak no stage exceeds.
inline void expect_memory_matches_seconds(const nlohmann::json& report) {
  ASSERT_TRUE(report.contains("memory") && report["memory"].is_object());
  const nlohmann::json& memory = report["memory"];
  const long faces = memory["input_faces"].get<long>();
  EXPECT_EQ(faces, report["mesh"]["faces"].get<long>());
  std::vector<std::string> stages, timed;
  for (const auto& [stage, s] : report["seconds"].items()) timed.push_back(stage);
  const long long process_peak = memory["peak_bytes"].get<long long>();
  for (const nlohmann::json& s : memory["stages"]) {
    stages.push_back(s["stage"].get<std::string>());
    const long long peak = s["peak_bytes"].get<long long>();
#ifdef __linux__
    EXPECT_GT(peak, 0) << stages.back();
#endif
    EXPECT_LE(peak, process_peak) << stages.back();
    EXPECT_EQ(s["bytes_per_face"].get<long long>(), std::llround(static_cast<double>(peak) / faces)) << stages.back();
  }
  std::sort(stages.begin(), stages.end());
  EXPECT_EQ(std::adjacent_find(stages.begin(), stages.end()), stages.end()) << "a stage is listed twice";
  EXPECT_EQ(stages, timed);  // the keys of "seconds" come sorted
}

/// The position of `stage` in the memory section's list (pipeline order), -1 if absent.
inline int memory_stage_index(const nlohmann::json& report, const std::string& stage) {
  const nlohmann::json& stages = report["memory"]["stages"];
  for (std::size_t i = 0; i < stages.size(); ++i)
    if (stages[i]["stage"] == stage) return static_cast<int>(i);
  return -1;
}

}  // namespace quadcover::testing
