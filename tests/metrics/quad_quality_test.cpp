// Quad mesh regularity (Table 7.1 metrics) and surface distance with known answers.
#include "metrics/quad_quality.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <random>

#include "mesh/triangle_tree.h"
#include "metrics/report.h"
#include "metrics/surface_distance.h"
#include "quad/extract_quads.h"
#include "quad/quad_test_maps.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// n×n grid of a×b rectangles in the plane z = 0.
std::pair<Eigen::MatrixX3d, std::vector<std::vector<int>>> rect_grid(int n, double a, double b) {
  Eigen::MatrixX3d V((n + 1) * (n + 1), 3);
  std::vector<std::vector<int>> F;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) V.row(j * (n + 1) + i) << a * i, b * j, 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      F.push_back({v, v + 1, v + n + 2, v + n + 1});
    }
  return {V, F};
}

TEST(QuadQuality, RegularGridIsPerfect) {
  const auto [V, F] = rect_grid(6, 1.0, 1.0);
  const QuadQuality q = quad_quality(V, F);
  EXPECT_NEAR(q.rsd_edge_length, 0, 1e-9);
  EXPECT_NEAR(q.rsd_corner_angle, 0, 1e-9);
  EXPECT_NEAR(q.mean_corner_angle, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(q.irregular_vertices, 0);
  EXPECT_EQ(q.valence_histogram.at(4), 25);
  EXPECT_EQ(q.valence_histogram.size(), 1u);
  EXPECT_EQ(q.boundary_vertices, 24);
  EXPECT_EQ(q.irregular_boundary_vertices, 0);
  EXPECT_EQ(q.non_quads, 0);
  EXPECT_TRUE(q.topology.manifold());
  EXPECT_EQ(q.topology.euler_characteristic, 1);
}

// Equal numbers of edges of length a and b: RSD = |a − b| / (a + b); right angles only.
TEST(QuadQuality, RectangularGridClosedForm) {
  const auto [V, F] = rect_grid(5, 1.0, 3.0);
  const QuadQuality q = quad_quality(V, F);
  EXPECT_NEAR(q.rsd_edge_length, 100.0 * 2.0 / 4.0, 1e-9);
  EXPECT_NEAR(q.rsd_corner_angle, 0, 1e-9);
  EXPECT_NEAR(q.mean_edge_length, 2.0, 1e-12);
}

TEST(QuadQuality, RhombusAnglesClosedForm) {
  // Sheared grid: corner angles alternate α and π − α: RSD = |π/2 − α| / (π/2).
  auto [V, F] = rect_grid(4, 1.0, 1.0);
  const double alpha = 1.2;
  for (int i = 0; i < V.rows(); ++i) {
    const double x = V(i, 0), y = V(i, 1);
    V(i, 0) = x + y * std::cos(alpha);
    V(i, 1) = y * std::sin(alpha);
  }
  const QuadQuality q = quad_quality(V, F);
  EXPECT_NEAR(q.rsd_corner_angle, 100.0 * std::abs(std::numbers::pi / 2 - alpha) / (std::numbers::pi / 2), 1e-9);
  EXPECT_NEAR(q.rsd_edge_length, 0, 1e-9);
}

TEST(QuadQuality, ExtractedCubeHasEightIrregularVertices) {
  const auto [mesh, param] = testing::cube_map(3, 4);
  const QuadMesh qm = extract_quads(mesh, param).mesh;
  const QuadQuality q = quad_quality(qm);
  EXPECT_EQ(q.irregular_vertices, 8);
  EXPECT_EQ(q.valence_histogram.at(3), 8);
  EXPECT_EQ(q.valence_histogram.at(4), 6 * 16 + 2 - 8);
  EXPECT_TRUE(q.topology.closed());
  // the cube's quads are exact squares of side 1/4: no spread at all
  EXPECT_NEAR(q.rsd_edge_length, 0, 1e-9);
  EXPECT_NEAR(q.rsd_corner_angle, 0, 1e-9);
  EXPECT_NEAR(q.mean_edge_length, 0.25, 1e-12);
  // the quads lie on the cube: zero distance both ways
  const SurfaceDistance d = surface_distance(qm.V, qm.faces, mesh.V(), mesh.F());
  EXPECT_LT(d.max, 1e-12);
}

TEST(SurfaceDistance, ClosestPointMatchesDenseSampling) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Eigen::Vector3d p(2 * u(rng), 2 * u(rng), 2 * u(rng));
    const double d = (closest_point_on_triangle(p, a, b, c) - p).norm();
    double best = 1e300;
    const int N = 300;
    for (int i = 0; i <= N; ++i)
      for (int j = 0; i + j <= N; ++j)
        best = std::min(best, (a + (b - a) * (double(i) / N) + (c - a) * (double(j) / N) - p).norm());
    EXPECT_LE(d, best + 1e-12);
    EXPECT_GE(d, best - 0.02);
  }
}

TEST(SurfaceDistance, TreeMatchesBruteForceOnBunny) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const TriangleTree tree(mesh.V(), mesh.F());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d p = mesh.V().row(trial * 37).transpose() + Eigen::Vector3d(u(rng), u(rng), u(rng));
    double brute = 1e300;
    for (int f = 0; f < mesh.num_faces(); ++f)
      brute = std::min(brute, (closest_point_on_triangle(p, mesh.V().row(mesh.F()(f, 0)), mesh.V().row(mesh.F()(f, 1)),
                                                         mesh.V().row(mesh.F()(f, 2))) - p).squaredNorm());
    EXPECT_DOUBLE_EQ(tree.squared_distance(p), brute);
    // closest_point: at that distance, on the face it names.
    int face = -1;
    const Eigen::Vector3d q = tree.closest_point(p, &face);
    ASSERT_GE(face, 0);
    EXPECT_DOUBLE_EQ((q - p).squaredNorm(), brute);
    EXPECT_EQ(q, closest_point_on_triangle(p, mesh.V().row(mesh.F()(face, 0)), mesh.V().row(mesh.F()(face, 1)),
                                           mesh.V().row(mesh.F()(face, 2))));
  }
}

// The queries run in parallel; the reduction is in sample order, so one thread and all threads agree bit for bit.
TEST(SurfaceDistance, SameValuesWithOneThreadAndAllThreads) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k.obj");
  // A "remesh" with holes: every other input triangle, so distances from the input are nonzero.
  std::vector<std::vector<int>> faces;
  for (int f = 0; f + 1 < mesh.num_faces(); f += 2) faces.push_back({mesh.F()(f, 0), mesh.F()(f, 1), mesh.F()(f, 2)});
  const SurfaceDistance all = surface_distance(mesh.V(), faces, mesh.V(), mesh.F());
  SurfaceDistance one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = surface_distance(mesh.V(), faces, mesh.V(), mesh.F());
  }
  EXPECT_GT(all.max_from_reference, 0.0);
  EXPECT_EQ(all.mean_to_reference, one.mean_to_reference);
  EXPECT_EQ(all.max_to_reference, one.max_to_reference);
  EXPECT_EQ(all.mean_from_reference, one.mean_from_reference);
  EXPECT_EQ(all.max_from_reference, one.max_from_reference);
  EXPECT_LT(all.max_to_reference, 1e-12);  // the remesh's samples lie on input triangles
}

TEST(SurfaceDistance, OffsetPlaneGivesOffsetOverDiagonal) {
  const Mesh ref = testing::make_grid(4);
  auto [V, F] = rect_grid(8, 0.125, 0.125);
  V.col(2).setConstant(0.01);
  const SurfaceDistance d = surface_distance(V, F, ref.V(), ref.F());
  EXPECT_NEAR(d.bbox_diagonal, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(d.mean, 0.01 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(d.max, 0.01 / std::sqrt(2.0), 1e-12);
}

TEST(Report, JsonHasFixedKeys) {
  Report r;
  r.input = "x.obj";
  const auto [V, F] = rect_grid(2, 1, 1);
  r.quad_mesh = quad_quality(V, F);
  const auto j = to_json(r);
  for (const char* k : {"input", "parameterization", "extraction", "quad_mesh", "surface_distance", "seconds", "values"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_TRUE(j["parameterization"].is_null());
  EXPECT_EQ(j["quad_mesh"]["quads"], 4);
  EXPECT_EQ(j["quad_mesh"]["valence_histogram"]["4"], 1);
  EXPECT_NE(to_text(r).find("RSD edge length"), std::string::npos);
}

}  // namespace
}  // namespace quadcover
