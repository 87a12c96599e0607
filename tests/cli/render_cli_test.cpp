// `quadcover render` through the real binary: textured, wireframe and UV-layout PNGs of files with per-corner vt,
// errors for impossible requests without partial outputs, and batch rendering into a folder.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;

using Result = quadcover::testing::CliRun;

Result run(const std::string& args) { return quadcover::testing::run_cli(args); }

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = quadcover::testing::fresh_dir("render_cli", "files");
    // A 4 × 4 grid of the unit square with per-corner vt = 4·(x, y): 16 checker squares, no seams.
    std::ofstream obj(dir / "grid.obj");
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) obj << "v " << i / 4.0 << ' ' << j / 4.0 << " 0\nvt " << i << ' ' << j << '\n';
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const int a = j * 5 + i + 1, b = a + 1, c = a + 6, d = a + 5;
        obj << "f " << a << '/' << a << ' ' << b << '/' << b << ' ' << c << '/' << c << '\n'
            << "f " << a << '/' << a << ' ' << c << '/' << c << ' ' << d << '/' << d << '\n';
      }
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string path(const std::string& name) const { return (dir / name).string(); }
  fs::path dir;
};

TEST_F(RenderCli, TexturedWireframeAndUvLayout) {
  Result r = run("render " + path("grid.obj") + " -o " + path("tex.png") + " --size 120x100 --json");
  ASSERT_EQ(r.code, 0);
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mode"], "textured");
  EXPECT_EQ(j["seam_edges"], 0);
  EXPECT_EQ(j["cones"], 0);
  EXPECT_EQ(j["width"], 120);
  EXPECT_GT(fs::file_size(path("tex.png")), 100u);

  r = run("render " + path("grid.obj") + " -o " + path("all.png") + " --size 100x100 --view all --json");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["width"], 3 * 100 + 2 * 8);

  r = run("render " + path("grid.obj") + " -o " + path("uv.png") + " --uv-layout --size 200x200 --json");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["flipped_triangles"], 0);

  r = run("render " + path("grid.obj") + " -o " + path("wire.png") + " --wireframe --view 30,20 --size 200x200 --json");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["mode"], "wireframe");
}

TEST_F(RenderCli, BadRequestsFailCleanlyWithoutOutput) {
  const std::string plain = quadcover::testing::data_path("eight_genus2");
  EXPECT_EQ(run("render " + plain + " -o " + path("x.png") + " --uv-layout").code, 2);  // no vt in the file
  EXPECT_EQ(run("render " + plain + " -o " + path("x.png") + " --size 10x5000000").code, 2);
  EXPECT_EQ(run("render " + plain + " -o " + path("x.png") + " --view diagonal").code, 2);
  EXPECT_EQ(run("render " + plain).code, 2);  // no output named
  EXPECT_FALSE(fs::exists(path("x.png")));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos);
}

TEST_F(RenderCli, BatchRendersEveryFileIntoTheOutputFolder) {
  fs::create_directories(dir / "in");
  fs::create_directories(dir / "out");
  fs::copy_file(dir / "grid.obj", dir / "in" / "a.obj");
  fs::copy_file(quadcover::testing::data_path("eight_genus2"), dir / "in" / "b.obj");
  const Result r = run("render " + path("in") + " -o " + path("out") + " --size 64x64 --json");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["succeeded"], 2);
  EXPECT_TRUE(fs::exists(dir / "out" / "a.png"));
  EXPECT_TRUE(fs::exists(dir / "out" / "b.png"));
}

}  // namespace
