// A degraded result is said on stderr, not only in the JSON: every warning of the report is printed, with -q too,
// and the report's surface_check agrees with an independent count of the written quad mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/read_mesh.h"
#include "pipeline/surface_check.h"
#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;

TEST(JobWarningsCli, EveryReportWarningIsOnStderrAndTheSurfaceCheckMatchesTheFile) {
  const fs::path dir = testing::fresh_dir("warnings_cli", "remesh");
  // Meshes whose default remesh is known to be clean (bunny_3k) or not (couplingdown_genus9 before injective maps).
  for (const char* name : {"bunny_3k", "couplingdown_genus9"}) {
    const std::string quads = (dir / "q.obj").string(), json = (dir / "q.json").string();
    const std::string err = (dir / "err.txt").string();
    const auto r =
        testing::run_cli("remesh " + testing::data_path(name) + " -o " + quads + " --report " + json + " -q", err);
    ASSERT_EQ(r.code, 0) << name << r.err;
    std::ifstream in(json);
    const nlohmann::json report = nlohmann::json::parse(in);
    for (const auto& w : report["warnings"])
      EXPECT_NE(r.err.find("warning: " + testing::data_path(name) + ": " + w.get<std::string>()), std::string::npos)
          << name << ": " << w << " not on stderr";
    const PolygonSoup soup = read_mesh(quads);
    std::vector<std::vector<int>> faces;
    for (std::size_t f = 0; f < soup.num_faces(); ++f)
      faces.emplace_back(soup.face_begin(f), soup.face_begin(f) + soup.face_size(f));
    const SurfaceCheck check =
        check_surface(testing::load_test_mesh(name), static_cast<int>(soup.num_vertices()), faces);
    EXPECT_EQ(report["surface_check"]["same_topology"].get<bool>(), check.same_topology) << name;
    EXPECT_EQ(report["surface_check"]["output"]["boundary_loops"].get<int>(), check.output.boundary_loops) << name;
    EXPECT_EQ(report["surface_check"]["problems"].size(), check.problems.size()) << name;
    if (!check.closed_all_quads) {
      EXPECT_FALSE(report["warnings"].empty()) << name;
    }
  }
  fs::remove_all(dir);
}

// A time limit already passed when the job starts: Algorithm 6.1 stops at once, the stages a valid result needs
// (the map with its untangling, the extraction, the checks) still run, every improving stage is skipped or cut short
// and named, the run says so on stderr and exits with 3 (partial result written), and the outputs are complete.
TEST(JobWarningsCli, APassedTimeLimitSkipsTheImprovingStagesAndExitsThree) {
  const fs::path dir = testing::fresh_dir("warnings_cli", "time");
  const std::string json = (dir / "q.json").string(), err = (dir / "err.txt").string(), obj = (dir / "q.obj").string();
  const auto r = testing::run_cli("remesh " + testing::data_path("bunny_3k") + " -o " + obj +
                                      " --optimize full --time-limit 0.001 --report " + json + " -q",
                                  err);
  ASSERT_EQ(r.code, 3) << r.err;
  std::ifstream in(json);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_TRUE(report["optimize"]["stopped_early"].get<bool>());
  const std::vector<std::string> cut = report["cut_short"].get<std::vector<std::string>>();
  for (const char* stage : {"keep-better", "relaxation", "quad smoothing"})
    EXPECT_NE(std::find(cut.begin(), cut.end(), stage), cut.end()) << stage << " not in cut_short";
  EXPECT_EQ(report["relaxation"]["iterations"].get<int>(), 0);
  EXPECT_EQ(report["quad_smoothing"]["iterations"].get<int>(), 0);
  EXPECT_NE(r.err.find("warning: "), std::string::npos);
  EXPECT_NE(r.err.find("skipped or cut short: keep-better"), std::string::npos) << r.err;
  EXPECT_TRUE(report["parameterization"]["seamless"].get<bool>());
  // The written quad mesh is the complete result the report describes.
  const PolygonSoup soup = read_mesh(obj);
  EXPECT_EQ(static_cast<int>(soup.num_faces()), report["quad_mesh"]["faces"].get<int>());
  EXPECT_GT(soup.num_faces(), 100u);
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos);
  fs::remove_all(dir);
}

// Without a stop nothing is cut short and the exit code is 0; a batch with a partial file exits 3 and names it.
TEST(JobWarningsCli, AGenerousTimeLimitCutsNothingAndABatchSaysPartial) {
  const fs::path dir = testing::fresh_dir("warnings_cli", "time_batch");
  const std::string json = (dir / "q.json").string();
  const auto ok = testing::run_cli("remesh " + testing::data_path("bunny_3k") + " -o " + (dir / "q.obj").string() +
                                   " --time-limit 600 --report " + json + " -q");
  ASSERT_EQ(ok.code, 0) << ok.err;
  std::ifstream in(json);
  EXPECT_TRUE(nlohmann::json::parse(in)["cut_short"].empty());
  const auto batch = testing::run_cli("remesh " + testing::data_path("bunny_3k") + " " + testing::data_path("torus_5k") +
                                      " -o " + (dir / "out").string() + " --time-limit 0.001 --json");
  EXPECT_EQ(batch.code, 3) << batch.err;
  const nlohmann::json summary = nlohmann::json::parse(batch.out);
  EXPECT_EQ(summary["partial"].get<int>(), 2);
  EXPECT_EQ(summary["failed"].get<int>(), 0);
  for (const auto& f : summary["files"]) {
    EXPECT_EQ(f["exit_code"].get<int>(), 3);
    EXPECT_TRUE(f["result"]["partial"].get<bool>());
  }
  fs::remove_all(dir);
}

// Dropping unreferenced vertices changes the output's vertex numbers: -q hides progress, never that warning.
TEST(JobWarningsCli, DroppedUnreferencedVerticesAreSaidWithQuietToo) {
  const fs::path dir = testing::fresh_dir("warnings_cli", "unreferenced");
  const std::string obj = (dir / "in.obj").string(), err = (dir / "err.txt").string();
  {
    std::ifstream src(testing::data_path("bunny_3k"));
    std::ofstream out(obj);
    out << src.rdbuf() << "\nv 100 100 100\n";  // used by no face
  }
  const auto r = testing::run_cli("remesh " + obj + " -o " + (dir / "q.obj").string() + " -q", err);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: " + obj + ": 1 unreferenced vertices (used by no face) dropped"), std::string::npos)
      << r.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadcover
