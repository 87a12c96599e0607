// The offscreen renderer: known scenes must produce images with predictable, countable properties.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/image.h"
#include "render/render_mesh.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::make_grid;
using testing::make_torus;

bool near(Rgb a, Rgb b, double tol = 0.02) {
  return std::abs(a.r - b.r) < tol && std::abs(a.g - b.g) < tol && std::abs(a.b - b.b) < tol;
}

int count_pixels(const Image& im, Rgb c, double tol = 0.02) {
  int n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) n += near(im.at(x, y), c, tol);
  return n;
}

// Per-corner UV of the unit-square grid: uv = (x + iy) * k.
Eigen::MatrixX3cd planar_uv(const Mesh& m, double k) {
  Eigen::MatrixX3cd uv(m.num_faces(), 3);
  for (int f = 0; f < m.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) uv(f, c) = k * std::complex<double>(m.V()(m.F()(f, c), 0), m.V()(m.F()(f, c), 1));
  return uv;
}

// Torus UVs from the two angles, unwrapped per face (so the map jumps along one meridian and one parallel).
Eigen::MatrixX3cd torus_uv(const Mesh& m, int n_major, int n_minor, double R) {
  Eigen::MatrixX3cd uv(m.num_faces(), 3);
  for (int f = 0; f < m.num_faces(); ++f) {
    double a0 = 0, b0 = 0;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p = m.V().row(m.F()(f, c));
      double a = std::atan2(p.y(), p.x()) * n_major / (2 * std::numbers::pi);
      double b = std::atan2(p.z(), std::hypot(p.x(), p.y()) - R) * n_minor / (2 * std::numbers::pi);
      if (c == 0) {
        a0 = a;
        b0 = b;
      } else {
        a += n_major * std::round((a0 - a) / n_major);
        b += n_minor * std::round((b0 - b) / n_minor);
      }
      uv(f, c) = {a, b};
    }
  }
  return uv;
}

TEST(UvLayout, UnitSquareCoversExpectedArea) {
  // Two triangles forming [0,1]²: the layout fills a square of side (1 - 2·margin)·size.
  Eigen::MatrixX3cd uv(2, 3);
  uv << std::complex<double>(0, 0), std::complex<double>(1, 0), std::complex<double>(1, 1), std::complex<double>(0, 0),
      std::complex<double>(1, 1), std::complex<double>(0, 1);
  UvLayoutOptions o;
  o.width = o.height = 200;
  o.margin = 0.1;
  o.edges = false;
  o.integer_grid = false;
  const Image im = render_uv_layout(uv, FlipReport{}, o);
  const int covered = im.width * im.height - count_pixels(im, o.background, 0.01);
  EXPECT_NEAR(covered, 160 * 160, 0.02 * 160 * 160);
  EXPECT_NEAR(count_pixels(im, o.fill), 160 * 160, 0.03 * 160 * 160);
  EXPECT_EQ(count_pixels(im, o.flipped, 0.1), 0);
  EXPECT_TRUE(near(im.at(100, 100), o.fill));
  EXPECT_TRUE(near(im.at(15, 100), o.background));
}

TEST(UvLayout, FlippedTrianglesAreRed) {
  const Mesh grid = make_grid(4);
  Eigen::MatrixX3cd uv = planar_uv(grid, 4.0);
  ASSERT_EQ(flipped_triangles(grid, uv).non_positive, 0);
  // Fold one triangle over by mirroring one corner through the opposite edge.
  const std::complex<double> a = uv(5, 1), b = uv(5, 2), c = uv(5, 0);
  const std::complex<double> d = (b - a) / std::abs(b - a);
  uv(5, 0) = a + d * std::conj((c - a) / d);
  const FlipReport flips = flipped_triangles(grid, uv);
  EXPECT_EQ(flips.flipped, 1);
  UvLayoutOptions o;
  o.width = o.height = 200;
  const Image im = render_uv_layout(uv, flips, o);
  const int red = count_pixels(im, o.flipped, 0.05);
  // Half a grid cell of (200·0.9/4)² px² is ≈ 1012 px², minus its drawn edges.
  EXPECT_GT(red, 600);
  EXPECT_LT(red, 1100);
  const Image clean = render_uv_layout(planar_uv(grid, 4.0), flipped_triangles(grid, planar_uv(grid, 4.0)), o);
  EXPECT_EQ(count_pixels(clean, o.flipped, 0.05), 0);
}

TEST(TexturedMesh, CheckerboardHasTheRightNumberOfSquaresAlongARow) {
  const Mesh grid = make_grid(10);
  const Eigen::MatrixX3cd uv = planar_uv(grid, 8.0);  // 8 × 8 squares on [0,1]²
  RenderOptions o;
  o.width = o.height = 240;
  o.show_seams = false;
  const Image im = render_textured_mesh(grid.V(), grid.F(), uv, {}, o);
  // Row through the middle of a square row: count light/dark runs inside the mesh.
  const int y = im.height / 2;  // v = 0.5 - 5 px: inside the fourth row of squares
  int runs = 0;
  bool prev_dark = false, inside = false;
  for (int x = 0; x < im.width; ++x) {
    const Rgb c = im.at(x, y + 5);
    if (near(c, o.background, 0.01)) {
      inside = false;
      continue;
    }
    const bool dark = c.b > c.r + 0.15;  // blue squares
    if (!inside || dark != prev_dark) ++runs;
    inside = true;
    prev_dark = dark;
  }
  EXPECT_EQ(runs, 8);
}

TEST(TexturedMesh, RenderingIsDeterministicAndPngRoundTrips) {
  const Mesh torus = make_torus(24, 12);
  const Eigen::MatrixX3cd uv = torus_uv(torus, 24, 12, 2.0);
  RenderOptions o;
  o.width = o.height = 160;
  o.camera = {30, 40};
  const Image a = render_textured_mesh(torus.V(), torus.F(), uv, {}, o);
  const Image b = render_textured_mesh(torus.V(), torus.F(), uv, {}, o);
  EXPECT_EQ(a.pixels, b.pixels);
  const Image back = decode_png(encode_png(a));
  EXPECT_EQ(back.width, a.width);
  EXPECT_EQ(back.pixels, a.pixels);
}

TEST(Seams, TorusAngleMapJumpsAlongOneMeridianAndOneParallel) {
  const int n_major = 24, n_minor = 12;
  const Mesh torus = make_torus(n_major, n_minor);
  const Eigen::MatrixX3cd uv = torus_uv(torus, n_major, n_minor, 2.0);
  EXPECT_EQ(uv_seam_edges(torus.F(), uv).size(), static_cast<std::size_t>(n_major + n_minor));
  EXPECT_TRUE(cones_from_uv(torus.F(), uv).empty());  // a flat torus has no cones
  EXPECT_TRUE(uv_seam_edges(make_grid(3).F(), planar_uv(make_grid(3), 1.0)).empty());
}

TEST(Seams, ConeIndexFromUvAngleSum) {
  // Three quarter planes around vertex 0: UV angle sum 3π/2, a cone of index 1/4 (quarter index +1);
  // five quarter planes: 5π/2, index -1/4. The ring vertices are boundary vertices and are skipped.
  for (int n : {3, 5}) {
    Eigen::MatrixX3i F(n, 3);
    Eigen::MatrixX3cd uv(n, 3);
    for (int i = 0; i < n; ++i) {
      F.row(i) << 0, 1 + i, 1 + (i + 1) % n;
      uv.row(i) << 0.0, 1.0, std::complex<double>(0, 1);
    }
    const auto cones = cones_from_uv(F, uv);
    ASSERT_EQ(cones.size(), 1u);
    EXPECT_EQ(cones[0].vertex, 0);
    EXPECT_EQ(cones[0].quarter_index, n == 3 ? 1 : -1);
  }
}

TEST(TexturedMesh, SeamsAndBranchPointsAreDrawnInTheirColours) {
  const Mesh torus = make_torus(24, 12);
  const Eigen::MatrixX3cd uv = torus_uv(torus, 24, 12, 2.0);
  RenderOptions o;
  o.width = o.height = 200;
  o.camera = {0, 60};
  o.texture = SurfaceTexture::None;
  const Image no_marks = [&] {
    RenderOptions p = o;
    p.show_seams = false;
    return render_textured_mesh(torus.V(), torus.F(), uv, {}, p);
  }();
  EXPECT_EQ(count_pixels(no_marks, o.seam_color, 0.05), 0);
  // Vertex 0 sits at angle 0 on the outer equator, visible from above-front.
  const Image marked = render_textured_mesh(torus.V(), torus.F(), uv, {{0, 1}, {6 * 12, -1}}, o);
  EXPECT_GT(count_pixels(marked, o.seam_color, 0.05), 20);
  EXPECT_GT(count_pixels(marked, branch_point_color(1), 0.05), 10);
  EXPECT_GT(count_pixels(marked, branch_point_color(-1), 0.05), 10);
}

TEST(PolygonMesh, WireframeShowsEveryGridLine) {
  // 4 × 4 quads on [0,1]²: a row through the middle crosses 5 vertical lines.
  Eigen::MatrixX3d V(25, 3);
  std::vector<std::vector<int>> quads;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) V.row(j * 5 + i) << i / 4.0, j / 4.0, 0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) quads.push_back({j * 5 + i, j * 5 + i + 1, (j + 1) * 5 + i + 1, (j + 1) * 5 + i});
  RenderOptions o;
  o.width = o.height = 200;
  o.line_width = 2;
  const Image im = render_polygon_mesh(V, quads, o);
  const int y = 100 + 12;  // inside the second row of quads, away from horizontal lines
  int lines = 0;
  bool in_line = false;
  for (int x = 0; x < im.width; ++x) {
    const bool dark = im.at(x, y).r < 0.4;
    lines += dark && !in_line;
    in_line = dark;
  }
  EXPECT_EQ(lines, 5);
  // Seen from the top, the flat grid is edge-on: almost nothing is drawn.
  o.camera = named_view("top");
  const Image top = render_polygon_mesh(V, quads, o);
  EXPECT_LT(top.width * top.height - count_pixels(top, o.background, 0.01), 0.05 * im.width * im.height);
}

TEST(Views, NamedViewsAndTiling) {
  EXPECT_EQ(named_view("side").azimuth_deg, 90);
  EXPECT_EQ(named_view("top").elevation_deg, 90);
  EXPECT_THROW(named_view("diagonal"), std::invalid_argument);
  const Image t = tile_horizontally({Image(10, 5, {0, 0, 0}), Image(20, 8, {1, 0, 0})}, 4);
  EXPECT_EQ(t.width, 34);
  EXPECT_EQ(t.height, 8);
  EXPECT_TRUE(near(t.at(16, 7), {1, 0, 0}));
  EXPECT_TRUE(near(t.at(5, 7), {1, 1, 1}));
}

}  // namespace
}  // namespace quadcover
