// `quadcover info` through the real binary: the exact JSON keys and topology of good meshes in every input
// format, exit status 2 with located messages on stderr for every broken file, and the repair options.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "io/read_mesh.h"
#include "io/write_off.h"
#include "io/write_ply.h"
#include "io/write_stl.h"
#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;

struct CliResult {
  int code = -1;
  std::string out, err;
};

// Runs the CLI with stdout and stderr captured in files of a per-test temporary directory.
class InfoCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = quadcover::testing::fresh_dir("info_test", ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  CliResult run(const std::string& args) const {
    const std::string out = file("stdout.txt"), err = file("stderr.txt");
    const std::string cmd = std::string(QUADCOVER_CLI) + " " + args + " >" + out + " 2>" + err;
    const int status = std::system(cmd.c_str());
    CliResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }
  static std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  fs::path dir_;
};

TEST_F(InfoCli, JsonKeysAndTopologyOfAGoodMesh) {
  const CliResult r = run("info --json " + testing::data_path("eight_genus2"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 315);
  EXPECT_EQ(j["faces"], 634);
  EXPECT_EQ(j["edges"], 315 + 634 - (2 - 2 * 2));
  EXPECT_EQ(j["components"], 1);
  EXPECT_EQ(j["boundary_loops"], 0);
  EXPECT_EQ(j["genus"], 2);
  EXPECT_EQ(j["euler_characteristic"], -2);
  EXPECT_EQ(j["manifold"], true);
  EXPECT_EQ(j["orientable"], true);
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_F(InfoCli, EveryInputFormatGivesTheSameTopology) {
  const Mesh m = testing::load_test_mesh("mech_holes_shark");
  write_off(file("m.off"), m.V(), m.F());
  write_ply(file("m.ply"), m.V(), m.F(), PlyEncoding::BinaryBigEndian);
  write_stl(file("m.stl"), m.V(), m.F(), /*binary=*/true);
  for (const char* name : {"m.off", "m.ply", "m.stl"}) {
    const CliResult r = run("info --json " + file(name));
    ASSERT_EQ(r.code, 0) << name << ": " << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["vertices"], m.num_vertices()) << name;
    EXPECT_EQ(j["faces"], m.num_faces()) << name;
    EXPECT_EQ(j["boundary_loops"], 4) << name;
    EXPECT_EQ(j["genus"], 0) << name;
  }
}

struct BadFile {
  const char* name;
  const char* kind;     // JSON problem kind expected among the problems
  const char* message;  // fragment expected on stderr
};

class InfoOnBadFiles : public InfoCli, public ::testing::WithParamInterface<BadFile> {};

TEST_P(InfoOnBadFiles, ExitStatus2WithLocatedProblems) {
  const BadFile bad = GetParam();
  const std::string path = testing::data_path(std::string("bad/") + bad.name);
  const CliResult r = run("info --json " + path);
  EXPECT_EQ(r.code, 2) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["valid"], false);
  bool found = false;
  for (const auto& p : j["problems"]) found |= p["kind"] == bad.kind;
  EXPECT_TRUE(found) << j["problems"].dump();
  EXPECT_NE(r.err.find(bad.message), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(path + ":"), std::string::npos) << "stderr should name file:line\n" << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Bad, InfoOnBadFiles,
    ::testing::Values(BadFile{"beetle_nonmanifold_edges", "non_manifold_edge", "47 non-manifold edges"},
                      BadFile{"blobby_inconsistent_orientation", "inconsistent_orientation", "3069 edges"},
                      BadFile{"cow_orig_nonmanifold_vertex", "non_manifold_vertex", "1 non-manifold vertex"},
                      BadFile{"dragon_res4_nonmanifold_dupfaces", "duplicate_face", "502 duplicate faces"},
                      BadFile{"fandisk_nonmanifold_edge_fin", "non_manifold_edge", "1 non-manifold edge"},
                      BadFile{"fertility_zero_area_face", "degenerate_face", "zero-area"},
                      BadFile{"spot_degenerate_face", "repeated_vertex", "repeated vertex"},
                      BadFile{"spot_duplicate_face", "duplicate_face", "1 duplicate face"},
                      BadFile{"spot_quads_nontriangle", "not_triangle", "quadcover repair"},
                      BadFile{"torus_klein_nonorientable", "non_orientable", "not orientable"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_F(InfoCli, ManifoldAndOrientableFlagsOfBadMeshes) {
  const nlohmann::json klein =
      nlohmann::json::parse(run("info --json " + testing::data_path("bad/torus_klein_nonorientable")).out);
  EXPECT_EQ(klein["orientable"], false);
  EXPECT_EQ(klein["manifold"], true);
  const nlohmann::json beetle =
      nlohmann::json::parse(run("info --json " + testing::data_path("bad/beetle_nonmanifold_edges")).out);
  EXPECT_EQ(beetle["manifold"], false);
}

TEST_F(InfoCli, RepairOptionsMakeBadMeshesValid) {
  const CliResult fixed = run("info --json --fix-orientation " + testing::data_path("bad/blobby_inconsistent_orientation"));
  ASSERT_EQ(fixed.code, 0) << fixed.err;
  EXPECT_EQ(nlohmann::json::parse(fixed.out)["genus"], 0);
  const CliResult tri = run("info --json --triangulate " + testing::data_path("bad/spot_quads_nontriangle"));
  ASSERT_EQ(tri.code, 0) << tri.err;
  EXPECT_EQ(nlohmann::json::parse(tri.out)["faces"], 2 * 2928);
}

TEST_F(InfoCli, UnreadableAndMalformedFilesExitWith2) {
  const CliResult missing = run("info " + file("does_not_exist.obj"));
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("does_not_exist.obj"), std::string::npos) << missing.err;

  {
    std::ofstream(file("broken.off")) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n";
  }
  const CliResult broken = run("info " + file("broken.off"));
  EXPECT_EQ(broken.code, 2);
  EXPECT_NE(broken.err.find(file("broken.off") + ":6:"), std::string::npos) << broken.err;

  {
    std::ofstream(file("mesh.xyz")) << "1 2 3\n";
  }
  const CliResult unknown = run("info " + file("mesh.xyz"));
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.err.find("unsupported mesh format"), std::string::npos) << unknown.err;
}

TEST_F(InfoCli, UnreferencedVerticesAreAWarningNotAnError) {
  {
    std::ofstream(file("iso.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n";
  }
  const CliResult r = run("info --json " + file("iso.obj"));
  EXPECT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 3);
  EXPECT_EQ(j["unreferenced_vertices_dropped"], 1);
  EXPECT_NE(r.err.find("warning: 1 unreferenced vertex (dropped)"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace quadcover
