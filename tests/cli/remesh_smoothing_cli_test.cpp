// `quadcover remesh --smooth-quads / --smooth-rigidity` through the real binary: smoothing moves vertices but keeps
// every face, evens out the quads, is reported, and bad values are refused without an output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;
using quadcover::testing::kWithoutRepairs;
using quadcover::testing::run_cli;
using quadcover::testing::slurp;

// The "v" and the "f" lines of an OBJ.
std::pair<std::vector<std::string>, std::vector<std::string>> obj_lines(const fs::path& p) {
  std::istringstream in(slurp(p));
  std::vector<std::string> v, f;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0) v.push_back(line);
    if (line.rfind("f ", 0) == 0) f.push_back(line);
  }
  return {v, f};
}

TEST(RemeshSmoothingCli, MovesVerticesKeepsFacesAndIsReported) {
  const fs::path dir = quadcover::testing::fresh_dir("remesh_smoothing", "files");
  const std::string in = quadcover::testing::data_path("fertility_genus4");
  const std::string raw = (dir / "raw.obj").string(), smooth = (dir / "smooth.obj").string();
  // The smoothing comes after the map: the repairs of its validity (kWithoutRepairs) are left out.
  ASSERT_EQ(
      run_cli("remesh " + in + " -o " + raw + kWithoutRepairs + " --smooth-quads 0 --report " +
              (dir / "raw.json").string() + " -q")
          .code,
      0);
  ASSERT_EQ(run_cli("remesh " + in + " -o " + smooth + kWithoutRepairs + " --report " + (dir / "smooth.json").string() +
                    " -q")
                .code,
            0);
  const auto [v0, f0] = obj_lines(raw);
  const auto [v1, f1] = obj_lines(smooth);
  EXPECT_EQ(f0, f1);
  ASSERT_EQ(v0.size(), v1.size());
  EXPECT_NE(v0, v1);
  const auto r0 = nlohmann::json::parse(slurp(dir / "raw.json")),
             r1 = nlohmann::json::parse(slurp(dir / "smooth.json"));
  EXPECT_EQ(r0["quad_smoothing"]["iterations"], 0);
  EXPECT_EQ(r1["quad_smoothing"]["iterations"], 20);
  EXPECT_GT(r1["quad_smoothing"]["mean_displacement"].get<double>(), 0.0);
  EXPECT_LT(r1["quad_mesh"]["rsd_edge_length"].get<double>(), r0["quad_mesh"]["rsd_edge_length"].get<double>());
  EXPECT_LT(r1["quad_mesh"]["rsd_corner_angle"].get<double>(), r0["quad_mesh"]["rsd_corner_angle"].get<double>());
  EXPECT_EQ(r1["parameterization"], r0["parameterization"]);

  const std::string bad = (dir / "bad.obj").string();
  for (const std::string option : {"--smooth-rigidity 1.5", "--smooth-quads -1"}) {
    const auto r = run_cli("remesh " + in + " -o " + bad + " " + option + " -q");
    EXPECT_NE(r.code, 0) << option;
    EXPECT_FALSE(fs::exists(bad)) << option;
  }
  fs::remove_all(dir);
}

}  // namespace
