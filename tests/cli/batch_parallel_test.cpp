// Batch mode of the heavy commands through the real binary: `quadcover param|remesh A B C D BAD -o DIR -j 2` runs
// the files in parallel (field, parameterization, optimization and extraction on two threads at once). Every
// output must be byte-identical to the one-file run of the same mesh, and the broken file fails alone (exit 2,
// its error in the summary, no output for it) while the others are written.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;

using quadcover::testing::CliRun;
using quadcover::testing::slurp;

CliRun run_with_long_timeout(const std::string& args) { return quadcover::testing::run_cli(args, "", 600); }

class BatchParallel : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("qc_batch_parallel_" + std::string(GetParam()) + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "single");
    fs::create_directories(dir_ / "batch");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_P(BatchParallel, OutputsMatchSingleRunsAndABadFileFailsAlone) {
  const std::string command = GetParam();
  const std::string suffix = command == std::string("param") ? ".param.obj" : ".quad.obj";
  const std::vector<std::string> meshes{"eight_genus2", "torus_5k", "bunny_3k", "lilium_disk"};
  const std::string bad = quadcover::testing::data_path("bad/beetle_nonmanifold_edges");

  std::string inputs;
  for (const auto& m : meshes) {
    inputs += quadcover::testing::data_path(m) + " ";
    const CliRun single = run_with_long_timeout(command + " " + quadcover::testing::data_path(m) + " -q -o " +
                                                (dir_ / "single" / (m + suffix)).string());
    ASSERT_EQ(single.code, 0) << m;
  }
  // The broken mesh sits in the middle of the list: the files after it must still run.
  inputs.insert(inputs.find(quadcover::testing::data_path("bunny_3k")), bad + " ");
  const CliRun batch = run_with_long_timeout(command + " " + inputs + "-j 2 --json -o " + (dir_ / "batch").string());
  EXPECT_EQ(batch.code, 2);  // the worst exit code: one bad input
  const auto j = nlohmann::json::parse(batch.out);
  ASSERT_EQ(j["files"].size(), meshes.size() + 1);
  EXPECT_EQ(j["succeeded"], static_cast<int>(meshes.size()));
  EXPECT_EQ(j["failed"], 1);
  // Results are listed in input order whatever the scheduling.
  EXPECT_FALSE(j["files"][2]["ok"]);
  EXPECT_EQ(j["files"][2]["exit_code"], 2);
  EXPECT_NE(j["files"][2]["error"].get<std::string>().find("beetle_nonmanifold_edges.obj:"), std::string::npos)
      << j["files"][2]["error"];
  EXPECT_FALSE(fs::exists(dir_ / "batch" / ("beetle_nonmanifold_edges" + suffix)));

  for (const auto& m : meshes) {
    const fs::path a = dir_ / "single" / (m + suffix), b = dir_ / "batch" / (m + suffix);
    ASSERT_TRUE(fs::exists(b)) << m;
    const std::string sa = slurp(a), sb = slurp(b);
    EXPECT_GT(sa.size(), 1000u) << m;
    EXPECT_TRUE(sa == sb) << m << ": batch output differs from the one-file run";
  }
  // Nothing but the outputs (no temporaries) is left in the folder.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "batch"), fs::directory_iterator{}),
            static_cast<long>(meshes.size()));
}

INSTANTIATE_TEST_SUITE_P(Commands, BatchParallel, ::testing::Values("param", "remesh"));

}  // namespace
