// Batch mode through the real binary: `quadcover info FOLDER FILE --json` processes every file, a broken one
// fails alone, and the exit code and JSON summary say so.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;

using quadcover::testing::CliRun;

using quadcover::testing::run_cli;

TEST(InfoBatch, FolderAndFileWithOneBrokenMesh) {
  const fs::path dir = quadcover::testing::fresh_dir("batch_cli", "files");
  fs::copy_file(quadcover::testing::data_path("eight_genus2"), dir / "a_eight.obj");
  fs::copy_file(quadcover::testing::data_path("bad/torus_klein_nonorientable"), dir / "b_klein.obj");
  const std::string extra = quadcover::testing::data_path("torus_5k");

  const CliRun r = run_cli("info --json -j 2 " + dir.string() + " " + extra);
  EXPECT_EQ(r.code, 2);  // one bad input
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["files"].size(), 3u);
  EXPECT_EQ(j["succeeded"], 2);
  EXPECT_EQ(j["failed"], 1);
  EXPECT_EQ(j["files"][0]["result"]["genus"], 2);
  EXPECT_FALSE(j["files"][1]["ok"]);
  EXPECT_NE(j["files"][1]["error"].get<std::string>().find("orientable"), std::string::npos);
  EXPECT_EQ(j["files"][2]["result"]["genus"], 1);

  // The text summary lists every file and the count; all good -> exit 0.
  fs::remove(dir / "b_klein.obj");
  const CliRun t = run_cli("info " + dir.string() + " " + extra);
  EXPECT_EQ(t.code, 0);
  EXPECT_NE(t.out.find("2 of 2 files succeeded"), std::string::npos);
  EXPECT_NE(t.out.find("a_eight.obj"), std::string::npos);
  fs::remove_all(dir);
}

// -q hides the per-file progress lines of a batch, never an error: each failed file is named with its message.
TEST(InfoBatch, QuietBatchStillNamesEveryFailure) {
  const fs::path dir = quadcover::testing::fresh_dir("batch_cli_quiet", "files");
  const std::string good = quadcover::testing::data_path("eight_genus2"),
                    bad = quadcover::testing::data_path("bad/torus_klein_nonorientable");
  const CliRun r = run_cli("field -q " + good + " " + bad + " -o " + dir.string(), (dir / "err.txt").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("error: " + bad), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("orientable"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("eight_genus2"), std::string::npos) << r.err;  // the good file: nothing
  fs::remove_all(dir);
}

TEST(InfoBatch, GlobalOptionsAreAcceptedAndValidated) {
  EXPECT_EQ(run_cli("info --time-limit 5 -q " + quadcover::testing::data_path("eight_genus2")).code, 0);
  EXPECT_EQ(run_cli("info --time-limit -1 " + quadcover::testing::data_path("eight_genus2")).code, 2);
  EXPECT_EQ(run_cli("info /no/such/file.obj").code, 2);
}

}  // namespace
