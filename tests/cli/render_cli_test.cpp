// `quadcover render` through the real binary: textured, wireframe and UV-layout PNGs of files with per-corner vt,
// errors for impossible requests without partial outputs, and batch rendering into a folder.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "render/image.h"
#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;

using Result = quadcover::testing::CliRun;

using quadcover::testing::run_cli;

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
  Result r = run_cli("render " + path("grid.obj") + " -o " + path("tex.png") + " --size 120x100 --json");
  ASSERT_EQ(r.code, 0);
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mode"], "textured");
  EXPECT_EQ(j["seam_edges"], 0);
  EXPECT_EQ(j["cones"], 0);
  EXPECT_EQ(j["width"], 120);
  {
    // The PNG decodes to the requested size, white at the corners (background), and the 4 × 4 checkerboard of the
    // vt is there: along every row and column that crosses the grid the dark squares form exactly 2 runs (D L D L),
    // never more.
    const quadcover::Image im = quadcover::read_png(path("tex.png"));
    ASSERT_EQ(im.width, 120);
    ASSERT_EQ(im.height, 100);
    for (auto [x, y] : {std::pair{0, 0}, {119, 0}, {0, 99}, {119, 99}}) {
      const quadcover::Rgb c = im.at(x, y);
      EXPECT_GT(std::min({c.r, c.g, c.b}), 0.99) << x << "," << y;
    }
    auto dark = [&](int x, int y) {
      const quadcover::Rgb c = im.at(x, y);
      return c.b > c.r + 0.15;
    };
    auto runs = [&](bool along_x, int k) {
      int n = 0;
      bool prev = false;
      for (int i = 0; i < (along_x ? im.width : im.height); ++i) {
        const bool d = along_x ? dark(i, k) : dark(k, i);
        n += d && !prev;
        prev = d;
      }
      return n;
    };
    int rows_with_two = 0, cols_with_two = 0;
    for (int y = 0; y < im.height; ++y) {
      EXPECT_LE(runs(true, y), 2) << "row " << y;
      rows_with_two += runs(true, y) == 2;
    }
    for (int x = 0; x < im.width; ++x) {
      EXPECT_LE(runs(false, x), 2) << "column " << x;
      cols_with_two += runs(false, x) == 2;
    }
    EXPECT_GT(rows_with_two, im.height / 4);
    EXPECT_GT(cols_with_two, im.height / 4);
  }

  r = run_cli("render " + path("grid.obj") + " -o " + path("all.png") + " --size 100x100 --view all --json");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["width"], 3 * 100 + 2 * 8);

  r = run_cli("render " + path("grid.obj") + " -o " + path("uv.png") + " --uv-layout --size 200x200 --json");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["flipped_triangles"], 0);

  r = run_cli("render " + path("grid.obj") + " -o " + path("wire.png") +
              " --wireframe --view 30,20 --size 200x200 --json");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["mode"], "wireframe");
}

TEST_F(RenderCli, BadRequestsFailCleanlyWithoutOutput) {
  const std::string plain = quadcover::testing::data_path("eight_genus2");
  EXPECT_EQ(run_cli("render " + plain + " -o " + path("x.png") + " --uv-layout").code, 2);  // no vt in the file
  EXPECT_EQ(run_cli("render " + plain + " -o " + path("x.png") + " --size 10x5000000").code, 2);
  EXPECT_EQ(run_cli("render " + plain + " -o " + path("x.png") + " --view diagonal").code, 2);
  EXPECT_EQ(run_cli("render " + plain).code, 2);  // no output named
  EXPECT_FALSE(fs::exists(path("x.png")));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos);
}

TEST_F(RenderCli, BatchRendersEveryFileIntoTheOutputFolder) {
  fs::create_directories(dir / "in");
  fs::create_directories(dir / "out");
  fs::copy_file(dir / "grid.obj", dir / "in" / "a.obj");
  fs::copy_file(quadcover::testing::data_path("eight_genus2"), dir / "in" / "b.obj");
  const Result r = run_cli("render " + path("in") + " -o " + path("out") + " --size 64x64 --json");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["succeeded"], 2);
  EXPECT_TRUE(fs::exists(dir / "out" / "a.png"));
  EXPECT_TRUE(fs::exists(dir / "out" / "b.png"));
}

}  // namespace
