// A degraded result is said on stderr, not only in the JSON: every warning of the report is printed, with -q too,
// and the report's surface_check agrees with an independent count of the written quad mesh.
#include <gtest/gtest.h>

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
    if (!check.closed_all_quads) EXPECT_FALSE(report["warnings"].empty()) << name;
  }
  fs::remove_all(dir);
}

// A time limit stops only Algorithm 6.1; the stages that make the result valid (relaxation, stiffening, the density,
// extraction, quad smoothing) still run, the run says so on stderr, and the whole command stays near the limit.
TEST(JobWarningsCli, ATimeLimitStopsTheOptimizationButNotTheStagesThatMakeTheResultValid) {
  const fs::path dir = testing::fresh_dir("warnings_cli", "time");
  const std::string json = (dir / "q.json").string(), err = (dir / "err.txt").string();
  const auto r = testing::run_cli("remesh " + testing::data_path("bunny_3k") + " -o " + (dir / "q.obj").string() +
                                      " --optimize full --max-iterations 0 --time-limit 1 --report " + json + " -q",
                                  err);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_TRUE(report["optimize"]["stopped_early"].get<bool>());
  EXPECT_GT(report["relaxation"]["iterations"].get<int>(), 0);
  EXPECT_GT(report["quad_smoothing"]["iterations"].get<int>(), 0);
  EXPECT_NE(r.err.find("the optimization was stopped early"), std::string::npos) << r.err;
  EXPECT_TRUE(report["parameterization"]["seamless"].get<bool>());
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
