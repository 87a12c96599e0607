// `param` / `remesh --fill propagate|smooth` through the real binary: the thesis's trusted propagation (5.1.2) is
// reachable from the jobs, it changes the field (branch points of the field stage, the written map), the default is
// the smooth fill (same bytes as `--fill smooth`), the report names the fill, and another word is refused (exit 2).
// Also the field stage's other choice, --split-cones.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;
using quadcover::testing::run_cli;
using quadcover::testing::slurp;

class FillCli : public quadcover::testing::FolderTest {
 protected:
  FillCli() : FolderTest("fill_cli") {}

  /// Runs `COMMAND bunny_3k -o NAME.obj --report NAME.json --optimize none EXTRA`; returns the report.
  nlohmann::json run(const std::string& command, const std::string& name, const std::string& extra) {
    return quadcover::testing::run_cli_report(command + " " + quadcover::testing::data_path("bunny_3k") + " -o " +
                                                  path(name + ".obj") + " --optimize none -q " + extra,
                                              path(name + ".json"));
  }
};

TEST_F(FillCli, PropagateChangesTheFieldAndTheDefaultIsSmooth) {
  const nlohmann::json by_default = run("param", "default", "");
  const nlohmann::json smooth = run("param", "smooth", "--fill smooth");
  const nlohmann::json propagate = run("param", "propagate", "--fill propagate");
  EXPECT_EQ(by_default["options"]["fill"], "smooth");
  EXPECT_EQ(propagate["options"]["fill"], "propagate");
  EXPECT_EQ(slurp(path("default.obj")), slurp(path("smooth.obj")));  // the default output is the smooth fill's
  // Propagation leaves more branch points in the field (seams between propagated regions, BENCHMARKS.md).
  const auto initial = [](const nlohmann::json& r) { return r["field"]["branch_points_initial"].get<int>(); };
  EXPECT_GT(initial(propagate), initial(smooth));
  EXPECT_NE(slurp(path("propagate.obj")), slurp(path("smooth.obj")));
  EXPECT_TRUE(propagate["parameterization"]["seamless"].get<bool>());
}

TEST_F(FillCli, RemeshTakesItToo) {
  const nlohmann::json propagate = run("remesh", "quads", "--fill propagate --smooth-quads 0");
  EXPECT_EQ(propagate["options"]["fill"], "propagate");
  EXPECT_GT(propagate["quad_mesh"]["quads"].get<int>(), 0);
}

// --split-cones N: cow's field has cones of index +3/4 and ±1/2; the default (2) splits them all into quarters and
// says how many quarters moved, 4 (whole turns only) moves none and writes another map; 1 is refused.
TEST_F(FillCli, SplitConesChoosesWhichSingularitiesAreSplit) {
  const auto run_cow = [&](const std::string& name, const std::string& extra) {
    return quadcover::testing::run_cli_report(
        "param " + quadcover::testing::data_path("cow") + " -o " + path(name + ".obj") + " --optimize none -q " + extra,
        path(name + ".json"));
  };
  const nlohmann::json by_default = run_cow("default", ""), whole_turns = run_cow("whole", "--split-cones 4");
  EXPECT_EQ(by_default["options"]["split_min_quarters"], 2);
  EXPECT_EQ(whole_turns["options"]["split_min_quarters"], 4);
  EXPECT_GE(by_default["field"]["singularity_moves"].get<int>(), 3 * 2 + 2 * 2);  // two +3/4, two ±1/2 at least
  EXPECT_EQ(whole_turns["field"]["singularity_moves"], 0);
  EXPECT_NE(slurp(path("default.obj")), slurp(path("whole.obj")));
  const auto r =
      run_cli("param " + quadcover::testing::data_path("cow") + " -o " + path("refused.obj") + " --split-cones 1 -q",
              path("err.txt"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--split-cones"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("refused.obj")));
}

// --square-holes N: the rims of couplingdown_genus9's small bolt holes are freed on the plate's side by default (8
// quad edges) and not with 0; a negative count is refused naming the option, with no output file.
TEST_F(FillCli, SquareHolesCountsQuadEdgesAndRefusesNegatives) {
  const auto run = [&](const std::string& name, const std::string& extra) {
    return quadcover::testing::run_cli_report("param " + quadcover::testing::data_path("couplingdown_genus9") + " -o " +
                                                  path(name + ".obj") +
                                                  " --optimize none --keep-better false --retries 0 -q " + extra,
                                              path(name + ".json"));
  };
  const nlohmann::json by_default = run("square", ""), off = run("round", "--square-holes 0");
  EXPECT_EQ(by_default["options"]["square_holes"], 8.0);
  EXPECT_GT(by_default["options"]["freed_hole_rims"].get<int>(), 0);
  EXPECT_EQ(off["options"]["square_holes"], 0.0);
  EXPECT_EQ(off["options"]["freed_hole_rims"], 0);
  const auto r = run_cli("param " + quadcover::testing::data_path("couplingdown_genus9") + " -o " +
                             path("refused.obj") + " --square-holes -1 -q",
                         path("err.txt"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--square-holes"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("refused.obj")));
}

TEST_F(FillCli, AnotherWordIsRefused) {
  for (const std::string command : {"param", "remesh"}) {
    SCOPED_TRACE(command);
    const std::string out = path("refused.obj");
    const auto r = run_cli(
        command + " " + quadcover::testing::data_path("bunny_3k") + " -o " + out + " --fill flood -q", path("err.txt"));
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--fill"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
