// The --report JSON of `param` and `remesh` carries the memory section (pipeline/job_report.h): a peak per timed
// stage, the CLI's reading first and writing last.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/report_memory.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;

TEST(ReportMemoryCli, ParamAndRemeshReportsHaveAPeakPerTimedStage) {
  const fs::path dir = testing::fresh_dir("report_memory_cli", "stages");
  const std::string input = testing::data_path("bunny_3k");
  for (const std::string command : {"param", "remesh"}) {
    const std::string out = (dir / (command + ".obj")).string(), report = (dir / (command + ".json")).string();
    const testing::CliRun run =
        testing::run_cli(command + " " + input + " -o " + out + " --report " + report + " -q", "", 300);
    ASSERT_EQ(run.code, 0) << command;
    const nlohmann::json r = nlohmann::json::parse(testing::slurp(report));
    testing::expect_memory_matches_seconds(r);
    const nlohmann::json& stages = r["memory"]["stages"];
    ASSERT_GE(stages.size(), 4u) << command;
    EXPECT_EQ(stages.front()["stage"], "read") << command;
    EXPECT_EQ(stages.back()["stage"], "write") << command;
    EXPECT_GE(testing::memory_stage_index(r, "field"), 1) << command;
    EXPECT_EQ(testing::memory_stage_index(r, "extract") >= 0, command == "remesh");
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadcover
