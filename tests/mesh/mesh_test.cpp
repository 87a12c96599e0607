// Mesh connectivity and geometry on real and generated meshes: topological invariants that break if the
// connectivity is wrong (χ, genus, boundary loops), and discrete Gauss–Bonnet for the angle defect.
#include "mesh/mesh.h"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "common/errors.h"
#include "io/read_mesh.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

struct Expected {
  const char* name;
  int genus, boundary_loops, vertices, faces;
};

class RealMesh : public ::testing::TestWithParam<Expected> {};

TEST_P(RealMesh, TopologyMatchesManifest) {
  const Expected ex = GetParam();
  const Mesh mesh = testing::load_test_mesh(ex.name);
  EXPECT_EQ(mesh.num_vertices(), ex.vertices);
  EXPECT_EQ(mesh.num_faces(), ex.faces);
  EXPECT_EQ(mesh.num_components(), 1);
  EXPECT_EQ(mesh.genus(), ex.genus);
  EXPECT_EQ(mesh.num_boundary_loops(), ex.boundary_loops);
  EXPECT_EQ(mesh.euler_characteristic(), 2 - 2 * ex.genus - ex.boundary_loops);
}

TEST_P(RealMesh, GaussBonnetHolds) {
  const Mesh mesh = testing::load_test_mesh(GetParam().name);
  EXPECT_NEAR(mesh.angle_defect().sum(), 2 * std::numbers::pi * mesh.euler_characteristic(), 1e-8);
}

TEST_P(RealMesh, EdgeFaceIncidenceIsConsistent) {
  const Mesh mesh = testing::load_test_mesh(GetParam().name);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, k);
      const int a = mesh.F()(f, (k + 1) % 3), b = mesh.F()(f, (k + 2) % 3);
      ASSERT_EQ(std::minmax(a, b), std::minmax(mesh.E()(e, 0), mesh.E()(e, 1)));
      ASSERT_EQ(mesh.FE_sign()(f, k), a < b ? 1 : -1);
      const int side = mesh.FE_sign()(f, k) > 0 ? 0 : 1;
      ASSERT_EQ(mesh.EF()(e, side), f);
      ASSERT_EQ(mesh.EF_corner()(e, side), k);
    }
}

TEST_P(RealMesh, FansCoverEveryCornerOnceAndAreOrdered) {
  const Mesh mesh = testing::load_test_mesh(GetParam().name);
  long corners = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto fan = mesh.fan(v);
    corners += static_cast<long>(fan.size());
    for (std::size_t i = 0; i + 1 < fan.size(); ++i)
      ASSERT_EQ(mesh.neighbor(fan[i].face, (fan[i].corner + 1) % 3), fan[i + 1].face) << "vertex " << v;
    if (mesh.is_boundary_vertex(v)) {
      ASSERT_LT(mesh.neighbor(fan.front().face, (fan.front().corner + 2) % 3), 0);
      ASSERT_LT(mesh.neighbor(fan.back().face, (fan.back().corner + 1) % 3), 0);
    }
  }
  EXPECT_EQ(corners, 3L * mesh.num_faces());
}

TEST_P(RealMesh, TransportMapsSharedEdgeDirection) {
  const Mesh mesh = testing::load_test_mesh(GetParam().name);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    const Eigen::Vector3d d = mesh.V().row(mesh.E()(e, 1)) - mesh.V().row(mesh.E()(e, 0));
    const Complex in_s = mesh.to_local(s, d), in_t = mesh.to_local(t, d);
    ASSERT_NEAR(std::abs(mesh.edge_transport()[e] * in_s - in_t), 0.0, 1e-9 * d.norm());
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, RealMesh,
                         ::testing::Values(Expected{"bunny_3k", 0, 0, 1839, 3674}, Expected{"torus_5k", 1, 0, 2304, 4608},
                                           Expected{"eight_genus2", 2, 0, 315, 634},
                                           Expected{"3holes_genus3", 3, 0, 3596, 7200},
                                           Expected{"fertility_genus4", 4, 0, 4494, 9000},
                                           Expected{"lilium_disk", 0, 1, 3389, 6590},
                                           Expected{"mech_holes_shark", 0, 4, 5246, 10192},
                                           Expected{"bunny_20k_holes", 0, 5, 10108, 19999},
                                           Expected{"couplingdown_genus9", 9, 0, 1841, 3714}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(GeneratedMesh, TorusAndGridTopology) {
  const Mesh torus = testing::make_torus(24, 12);
  EXPECT_EQ(torus.genus(), 1);
  EXPECT_EQ(torus.euler_characteristic(), 0);
  const Mesh grid = testing::make_grid(5);
  EXPECT_EQ(grid.num_boundary_loops(), 1);
  EXPECT_EQ(grid.boundary_loops()[0].size(), 20u);
  EXPECT_NEAR(grid.total_area(), 1.0, 1e-12);
  EXPECT_EQ(grid.total_area(), grid.face_areas().sum());  // cached, the same sum
  const Mesh cyl = testing::make_cylinder(16, 4);
  EXPECT_EQ(cyl.num_boundary_loops(), 2);
  EXPECT_EQ(cyl.genus(), 0);
}

TEST(GeneratedMesh, ManyComponentsCountedSeparately) {
  const Mesh a = testing::make_torus(8, 6);
  Eigen::MatrixX3d V(2 * a.num_vertices(), 3);
  V << a.V(), a.V().rowwise() + Eigen::RowVector3d(10, 0, 0);
  Eigen::MatrixX3i F(2 * a.num_faces(), 3);
  F << a.F(), a.F().array() + a.num_vertices();
  const Mesh two = Mesh::from_triangles(V, F);
  ASSERT_EQ(two.num_components(), 2);
  EXPECT_EQ(two.components()[0].genus, 1);
  EXPECT_EQ(two.components()[1].genus, 1);
  EXPECT_EQ(two.genus(), 2);
}

TEST(GeneratedMesh, BoundaryLoopKeepsSurfaceOnTheLeft) {
  const Mesh grid = testing::make_grid(3);
  const auto& loop = grid.boundary_loops()[0];
  double signed_area = 0;  // shoelace: positive for a counter-clockwise loop
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto p = grid.V().row(loop[i]), q = grid.V().row(loop[(i + 1) % loop.size()]);
    signed_area += p.x() * q.y() - q.x() * p.y();
  }
  EXPECT_GT(signed_area, 0);
}

}  // namespace
}  // namespace quadcover

namespace quadcover {
namespace {

// Issue 18 item 11: the error's headline counts the kinds of problem it lists (the count was read after the list
// had been moved into the exception, so it always said 0).
TEST(BuildMesh, ErrorCountsTheKindsOfProblemItLists) {
  PolygonSoup soup;
  soup.file = "two_problems.obj";
  soup.positions.resize(4, 3);
  soup.positions << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, std::numeric_limits<double>::quiet_NaN();
  const std::int64_t a[3] = {0, 1, 2}, b[3] = {0, 1, 7};  // a NaN vertex (3 is unused) and an index out of range
  soup.add_face(a, 3, 1);
  soup.add_face(b, 3, 2);
  soup.positions(0, 0) = std::numeric_limits<double>::infinity();
  try {
    (void)build_mesh(soup);
    FAIL() << "invalid mesh accepted";
  } catch (const TopologyError& e) {
    ASSERT_EQ(e.problems().size(), 2u);
    EXPECT_NE(std::string(e.what()).find("(2 kinds of problem)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace quadcover
