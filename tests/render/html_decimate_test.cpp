// The HTML report's 3D views: seams and branch points found from the per-corner uv (a cube parameterized one chart
// per side: seams on the cube's edges, 8 cones of index +1/4 at its corners) are in the page data; a ~200k-face
// input is decimated by vertex clustering so that the page stays under 5 MB, says so, and keeps its seams and
// branch points; the page opens on the views and key numbers with the long table last.
#include "render/html_decimate.h"

#include <gtest/gtest.h>

#include <map>

#include "render/html_report.h"
#include "support/text.h"

namespace quadcover {
namespace {

using testing::between;

/// The surface of [0, 1]³ with n × n squares per side, as triangles with per-corner uv = the side's grid
/// coordinates (one chart per side: a seamless map with a cone at each corner), and as quads.
struct Cube {
  HtmlMesh textured, quads;
};
Cube make_cube(int n) {
  const Eigen::Vector3d origin[6] = {{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}};
  const Eigen::Vector3d du[6] = {{0, 1, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 0, 1}, {0, 1, 0}};
  const Eigen::Vector3d dv[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // du × dv out
  std::map<std::array<int, 3>, int> id;
  std::vector<Eigen::Vector3d> points;
  auto vertex = [&](int side, int a, int b) {
    const Eigen::Vector3d p = origin[side] + (du[side] * a + dv[side] * b) / n;
    const std::array<int, 3> key{static_cast<int>(std::lround(p.x() * n)), static_cast<int>(std::lround(p.y() * n)),
                                 static_cast<int>(std::lround(p.z() * n))};
    const auto [it, fresh] = id.emplace(key, static_cast<int>(points.size()));
    if (fresh) points.push_back(p);
    return it->second;
  };
  Cube c;
  std::vector<std::complex<double>> uv;
  for (int s = 0; s < 6; ++s)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const int v00 = vertex(s, a, b), v10 = vertex(s, a + 1, b), v11 = vertex(s, a + 1, b + 1),
                  v01 = vertex(s, a, b + 1);
        c.quads.faces.push_back({v00, v10, v11, v01});
        c.textured.faces.push_back({v00, v10, v11});
        c.textured.faces.push_back({v00, v11, v01});
        for (const auto& z : {std::complex<double>(a, b),
                              {a + 1.0, b + 0.0},
                              {a + 1.0, b + 1.0},
                              std::complex<double>(a, b),
                              {a + 1.0, b + 1.0},
                              {a + 0.0, b + 1.0}})
          uv.push_back(z);
      }
  Eigen::MatrixX3d V(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) V.row(static_cast<Eigen::Index>(i)) = points[i];
  c.textured.V = c.quads.V = V;
  c.textured.uv.resize(static_cast<Eigen::Index>(c.textured.faces.size()), 3);
  for (std::size_t k = 0; k < uv.size(); ++k) c.textured.uv(static_cast<Eigen::Index>(k / 3), k % 3) = uv[k];
  c.textured.name = "parameterization";
  c.quads.name = "quad mesh";
  c.quads.wireframe = true;
  return c;
}

bool on_cube_edge(const Eigen::Vector3d& p, double tol) {
  int extreme = 0;
  for (int d = 0; d < 3; ++d) extreme += std::min(std::abs(p[d]), std::abs(p[d] - 1)) < tol;
  return extreme >= 2;
}

nlohmann::json page_data(const std::string& page) {
  return nlohmann::json::parse(between(page, "<script type=\"application/json\" id=\"qc-data\">", "</script>"));
}

Eigen::Vector3d position(const nlohmann::json& mesh, int v) {
  const auto& P = mesh["positions"];
  return {P[3 * v].get<double>(), P[3 * v + 1].get<double>(), P[3 * v + 2].get<double>()};
}

TEST(HtmlViews, SeamsAndBranchPointsFromTheUvAreInThePageData) {
  const Cube cube = make_cube(6);
  HtmlReport r;
  r.meshes = {cube.textured, cube.quads};
  r.metrics = {{"mesh", {{"faces", 432}}}, {"parameterization", {{"branch_points", 8}, {"seamless", true}}}};
  const std::string page = html_report(r);
  const nlohmann::json data = page_data(page);
  const nlohmann::json& m = data["meshes"][0];
  ASSERT_EQ(m["branch_points"].size(), 8u);
  for (const auto& b : m["branch_points"]) {
    EXPECT_EQ(b["quarter_index"], 1);  // three right angles: Θ = 3π/2
    const Eigen::Vector3d p = position(m, b["vertex"]);
    for (int d = 0; d < 3; ++d) EXPECT_TRUE(p[d] == 0 || p[d] == 1) << p.transpose();
  }
  const auto& seams = m["seams"];
  ASSERT_GT(seams.size(), 0u);
  for (std::size_t i = 0; i < seams.size(); ++i) EXPECT_TRUE(on_cube_edge(position(m, seams[i]), 1e-12));
  EXPECT_TRUE(data["meshes"][1]["seams"].empty());  // the quad mesh has no uv
  EXPECT_FALSE(m.contains("decimated"));
  EXPECT_EQ(page.find("qc-decimated"), std::string::npos);
  // First the views and the key numbers, the long table last.
  const auto views = page.find("<canvas"), key = page.find("id=\"qc-key\""), table = page.find("id=\"qc-metrics\"");
  ASSERT_NE(key, std::string::npos);
  EXPECT_LT(views, table);
  EXPECT_LT(key, table);
  EXPECT_NE(between(page, "<table id=\"qc-key\">", "</table>").find("<td>branch points</td><td class=\"v\">8</td>"),
            std::string::npos);
}

TEST(HtmlViews, DecimationKeepsTheBudgetTheSeamsAndTheCones) {
  const Cube cube = make_cube(60);  // 43200 triangles, 21600 quads
  for (const std::size_t budget : {20000u, 5000u, 500u}) {
    SCOPED_TRACE(budget);
    HtmlMesh full = cube.textured;
    full.seams = {{0, 1}};  // given seams and branch points are carried over, not recomputed
    full.branch_points = {{0, 1}, {static_cast<int>(full.V.rows()) - 1, -1}};
    const HtmlMesh d = decimate_display_mesh(full, budget);
    EXPECT_LE(d.faces.size(), budget);
    EXPECT_GT(d.faces.size(), budget / 5);  // not far below it either
    EXPECT_EQ(d.decimated_from, full.faces.size());
    EXPECT_EQ(d.uv.rows(), static_cast<Eigen::Index>(d.faces.size()));
    for (const auto& f : d.faces) {
      ASSERT_EQ(f.size(), 3u);
      for (int v : f) ASSERT_TRUE(v >= 0 && v < d.V.rows());
      EXPECT_TRUE(f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
    }
    // Cluster centres are means of vertices of one cell: inside the cube and within a cell of a corner vertex.
    EXPECT_GE(d.V.minCoeff(), 0.0);
    EXPECT_LE(d.V.maxCoeff(), 1.0);
    ASSERT_EQ(d.branch_points.size(), 2u);
    EXPECT_LT(d.V.row(d.branch_points[0].vertex).norm(), std::sqrt(3.0) * d.cell_size);
    EXPECT_EQ(d.branch_points[1].quarter_index, -1);
    const HtmlMesh q = decimate_display_mesh(cube.quads, budget);
    EXPECT_LE(q.faces.size(), budget);
    EXPECT_GT(q.faces.size(), budget / 5);
  }
  const HtmlMesh small = decimate_display_mesh(cube.quads, cube.quads.faces.size());
  EXPECT_EQ(small.decimated_from, 0u);
  EXPECT_EQ(small.faces, cube.quads.faces);
}

TEST(HtmlViews, PageOfA200kFaceInputStaysUnder5MB) {
  const Cube cube = make_cube(130);  // 202800 triangles, 101400 quads
  ASSERT_GT(cube.textured.faces.size(), 200000u);
  HtmlReport r;
  r.meshes = {cube.textured, cube.quads};
  r.metrics = {{"mesh", {{"faces", cube.textured.faces.size()}}}};
  const std::string page = html_report(r);
  EXPECT_LT(page.size(), 5u << 20) << page.size();
  EXPECT_NE(page.find("id=\"qc-decimated\""), std::string::npos);
  EXPECT_NE(page.find("of 202800 faces"), std::string::npos);
  const nlohmann::json data = page_data(page);
  for (const auto& m : data["meshes"]) {
    ASSERT_TRUE(m.contains("decimated")) << m["name"];
    EXPECT_LE(m["decimated"]["faces"].get<std::size_t>(), r.max_display_faces);
  }
  const nlohmann::json& m = data["meshes"][0];
  EXPECT_EQ(m["decimated"]["original_faces"], 202800);
  EXPECT_EQ(m["branch_points"].size(), 8u);  // the cube's corners, found on the full mesh
  for (const auto& b : m["branch_points"]) {
    const Eigen::Vector3d p = position(m, b["vertex"]);
    for (int d = 0; d < 3; ++d) EXPECT_LT(std::min(p[d], 1 - p[d]), 2 * m["decimated"]["cell_size"].get<double>());
  }
  ASSERT_GT(m["seams"].size(), 0u);
  const double cell = m["decimated"]["cell_size"];
  for (std::size_t i = 0; i < m["seams"].size(); ++i) EXPECT_TRUE(on_cube_edge(position(m, m["seams"][i]), cell));
}

}  // namespace
}  // namespace quadcover
