// Adversarial but valid inputs (issue 8): slivers, extreme scales, huge valence, many components, tiny meshes,
// flat disks, thousands of boundary loops. Each must build with the right topology (χ = V - E + F, genus,
// boundary loops) and finite geometry satisfying discrete Gauss–Bonnet (Def. 1.8), or fail with a clear message.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/errors.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

constexpr double kPi = std::numbers::pi;

// Geometry must be finite everywhere and the angle defects must sum to 2πχ (discrete Gauss–Bonnet).
void expect_sane_geometry(const Mesh& m) {
  EXPECT_TRUE(m.face_areas().allFinite());
  EXPECT_TRUE((m.face_areas().array() > 0).all());
  EXPECT_TRUE(m.corner_angles().allFinite());
  EXPECT_TRUE(m.corner_cotangents().allFinite());
  EXPECT_TRUE(m.edge_transport().allFinite());
  EXPECT_NEAR(m.angle_defect().sum(), 2 * kPi * m.euler_characteristic(), 1e-6 * (1 + m.num_vertices()));
}

PolygonSoup soup_of(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) { return PolygonSoup::from_triangles(V, F); }

TEST(Adversarial, SingleTriangle) {
  Eigen::MatrixX3d V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Eigen::MatrixX3i F(1, 3);
  F << 0, 1, 2;
  const Mesh m = build_mesh(soup_of(V, F)).mesh;
  EXPECT_EQ(m.num_edges(), 3);
  EXPECT_EQ(m.euler_characteristic(), 1);
  EXPECT_EQ(m.genus(), 0);
  ASSERT_EQ(m.num_boundary_loops(), 1);
  EXPECT_EQ(m.boundary_loops()[0].size(), 3u);
  expect_sane_geometry(m);
}

TEST(Adversarial, Tetrahedron) {
  Eigen::MatrixX3d V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixX3i F(4, 3);
  F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  const Mesh m = build_mesh(soup_of(V, F)).mesh;
  EXPECT_EQ(m.num_edges(), 6);
  EXPECT_EQ(m.euler_characteristic(), 2);
  EXPECT_EQ(m.genus(), 0);
  EXPECT_EQ(m.num_boundary_loops(), 0);
  for (int v = 0; v < 4; ++v) EXPECT_EQ(m.valence(v), 3);
  expect_sane_geometry(m);
}

TEST(Adversarial, FlatDiskHasZeroInteriorCurvature) {
  const Mesh m = testing::make_grid(30);
  EXPECT_EQ(m.euler_characteristic(), 1);
  EXPECT_EQ(m.num_boundary_loops(), 1);
  for (int v = 0; v < m.num_vertices(); ++v)
    if (!m.is_boundary_vertex(v)) {
      ASSERT_NEAR(m.angle_defect()[v], 0.0, 1e-12);
    }
  expect_sane_geometry(m);
}

TEST(Adversarial, ValenceOneThousand) {
  const Mesh disk = testing::make_fan(1000, false);
  EXPECT_EQ(disk.valence(0), 1000);
  EXPECT_EQ(disk.num_boundary_loops(), 1);
  EXPECT_EQ(disk.euler_characteristic(), 1);
  EXPECT_EQ(disk.fan(0).size(), 1000u);
  expect_sane_geometry(disk);
  const Mesh bipyramid = testing::make_fan(1000, true);
  EXPECT_EQ(bipyramid.valence(0), 1000);
  EXPECT_EQ(bipyramid.valence(1001), 1000);
  EXPECT_EQ(bipyramid.genus(), 0);
  EXPECT_EQ(bipyramid.num_boundary_loops(), 0);
  expect_sane_geometry(bipyramid);
}

// Connectivity at a vertex of valence 100000. Its cost (linear in the valence, not quadratic) is measured by
// bench_io's BM_HighValenceFan, not asserted here: no timed assertions in tests.
TEST(Adversarial, ValenceOneHundredThousand) {
  const Mesh bipyramid = testing::make_fan(100000, true);
  EXPECT_EQ(bipyramid.valence(0), 100000);
  EXPECT_EQ(bipyramid.fan(0).size(), 100000u);
  EXPECT_EQ(bipyramid.euler_characteristic(), 2);
}

TEST(Adversarial, SliversAndNearDegenerateTriangles) {
  // A grid whose middle row is squashed to relative height 1e-9: needle triangles with angles near 0 and π.
  Mesh grid = testing::make_grid(10);
  Eigen::MatrixX3d V = grid.V();
  for (int v = 0; v < V.rows(); ++v)
    if (V(v, 1) > 0.55) V(v, 1) = 0.5 + 1e-9 + (V(v, 1) - 0.6);
  const Mesh m = build_mesh(soup_of(V, grid.F())).mesh;
  EXPECT_EQ(m.euler_characteristic(), 1);
  EXPECT_LT(m.face_areas().minCoeff(), 1e-9);
  EXPECT_LT(m.corner_angles().minCoeff(), 1e-7);
  expect_sane_geometry(m);
  // Pushed below the round-off tolerance the needles are reported as degenerate, with their faces.
  for (int v = 0; v < V.rows(); ++v)
    if (V(v, 1) > 0.5 && V(v, 1) < 0.5 + 2e-9) V(v, 1) = 0.5 + 1e-14;
  const ValidationReport r = validate(soup_of(V, grid.F()));
  EXPECT_TRUE(r.has(ProblemKind::DegenerateFace));
  EXPECT_THROW(build_mesh(soup_of(V, grid.F())), TopologyError);
}

class ExtremeScale : public ::testing::TestWithParam<double> {};

TEST_P(ExtremeScale, BunnyScaledKeepsTopologyAndAngles) {
  const double s = GetParam();
  const Mesh ref = testing::load_test_mesh("bunny_3k");
  PolygonSoup soup = read_mesh(testing::data_path("bunny_3k"));
  soup.positions *= s;
  const MeshBuildResult built = build_mesh(soup);
  EXPECT_TRUE(built.report.problems.empty());
  const Mesh& m = built.mesh;
  EXPECT_EQ(m.genus(), 0);
  EXPECT_EQ(m.num_edges(), ref.num_edges());
  // Angles are scale invariant, areas scale with s².
  EXPECT_LT((m.corner_angles() - ref.corner_angles()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(m.total_area() / (s * s), ref.total_area(), 1e-9 * ref.total_area());
  expect_sane_geometry(m);
}

INSTANTIATE_TEST_SUITE_P(Scales, ExtremeScale, ::testing::Values(1e-9, 1e9));

TEST(Adversarial, ManyComponents) {
  // 2000 disjoint tetrahedra in a row.
  const int n = 2000;
  Eigen::MatrixX3d V(4 * n, 3);
  Eigen::MatrixX3i F(4 * n, 3);
  for (int c = 0; c < n; ++c) {
    V.middleRows(4 * c, 4) << 3.0 * c, 0, 0, 3.0 * c + 1, 0, 0, 3.0 * c, 1, 0, 3.0 * c, 0, 1;
    F.middleRows(4 * c, 4) << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
    F.middleRows(4 * c, 4).array() += 4 * c;
  }
  const Mesh m = build_mesh(soup_of(V, F)).mesh;
  ASSERT_EQ(m.num_components(), n);
  EXPECT_EQ(m.euler_characteristic(), 2 * n);
  EXPECT_EQ(m.genus(), 0);
  for (const ComponentInfo& c : m.components()) {
    ASSERT_EQ(c.euler_characteristic, 2);
    ASSERT_EQ(c.faces, 4);
  }
  expect_sane_geometry(m);
}

TEST(Adversarial, ThousandsOfBoundaryLoops) {
  // A 100 × 100 grid with the quads (2a+1, 2b+1), a, b < 49, removed: 2401 separate square holes.
  const int n = 100;
  const Mesh grid = testing::make_grid(n);
  const Eigen::MatrixX3i F = testing::grid_faces_with_holes(grid, n);
  const Mesh m = build_mesh(soup_of(grid.V(), F)).mesh;
  EXPECT_EQ(m.num_components(), 1);
  EXPECT_EQ(m.num_boundary_loops(), 1 + 49 * 49);
  EXPECT_EQ(m.genus(), 0);
  EXPECT_EQ(m.euler_characteristic(), 1 - 49 * 49);
  std::size_t four = 0;
  for (const auto& loop : m.boundary_loops()) four += loop.size() == 4;
  EXPECT_EQ(four, 49u * 49u);
  expect_sane_geometry(m);
}

TEST(Adversarial, OverflowingCoordinatesFailWithAClearMessage) {
  // Coordinates near the double range: edge vectors overflow to inf. Not silently accepted.
  PolygonSoup soup = read_mesh(testing::data_path("eight_genus2"));
  soup.positions *= 1e306;
  soup.positions.col(0) *= 1e3;  // some coordinates become inf
  const ValidationReport r = validate(soup);
  EXPECT_FALSE(r.valid());
  ASSERT_FALSE(r.problems.empty());
  EXPECT_NE(r.problems[0].message.find("eight_genus2.obj:"), std::string::npos) << r.problems[0].message;
}

}  // namespace
}  // namespace quadcover
