// check_surface: the counts of a polygon mesh against direct constructions, and every kind of difference named.
#include "pipeline/surface_check.h"

#include <gtest/gtest.h>

#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// An n×m quad grid on a torus (closed, χ = 0) or a square (one boundary loop, χ = 1).
std::vector<std::vector<int>> quad_grid(int n, int m, bool torus) {
  std::vector<std::vector<int>> faces;
  const int cols = torus ? n : n + 1, rows = torus ? m : m + 1;
  auto id = [&](int i, int j) { return (j % rows) * cols + (i % cols); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  (void)rows;
  return faces;
}

TEST(SurfaceCheck, CountsOfQuadGridsAreTheirTopology) {
  const SurfaceCounts torus = surface_counts(8 * 6, quad_grid(8, 6, true));
  EXPECT_EQ(torus.components, 1);
  EXPECT_EQ(torus.boundary_loops, 0);
  EXPECT_EQ(torus.euler_characteristic, 0);
  EXPECT_EQ(torus.non_quads, 0);
  const SurfaceCounts square = surface_counts(9 * 7, quad_grid(8, 6, false));
  EXPECT_EQ(square.boundary_loops, 1);
  EXPECT_EQ(square.euler_characteristic, 1);
  // Two copies: two components, each counted.
  auto faces = quad_grid(8, 6, false);
  for (auto f : quad_grid(8, 6, false)) {
    for (int& v : f) v += 63;
    faces.push_back(f);
  }
  const SurfaceCounts two = surface_counts(126, faces);
  EXPECT_EQ(two.components, 2);
  EXPECT_EQ(two.boundary_loops, 2);
  EXPECT_EQ(two.euler_characteristic, 2);
}

TEST(SurfaceCheck, SameTopologyPassesAndEveryChangeIsNamed) {
  const Mesh torus = testing::make_torus(16, 8);
  const SurfaceCheck same = check_surface(torus, 48, quad_grid(8, 6, true));
  EXPECT_TRUE(same.same_topology);
  EXPECT_TRUE(same.closed_all_quads);
  EXPECT_TRUE(same.problems.empty());
  // A quad torus with one face cut out: a hole, χ off by one, and not closed.
  auto holed = quad_grid(8, 6, true);
  holed.erase(holed.begin() + 10);
  const SurfaceCheck hole = check_surface(torus, 48, holed);
  EXPECT_FALSE(hole.same_topology);
  EXPECT_FALSE(hole.closed_all_quads);
  ASSERT_EQ(hole.problems.size(), 2u);
  EXPECT_NE(hole.problems[0].find("boundary loops: 1 in the quad mesh, 0 in the input"), std::string::npos);
  EXPECT_NE(hole.problems[1].find("Euler characteristic"), std::string::npos);
  // Two quads merged into a hexagon: same topology, but a closed input deserves all quads.
  auto merged = quad_grid(8, 6, true);
  merged[0] = {0, 1, 2, 10, 9, 8};
  merged.erase(merged.begin() + 1);
  const SurfaceCheck hex = check_surface(torus, 48, merged);
  EXPECT_TRUE(hex.same_topology) << (hex.problems.empty() ? "" : hex.problems[0]);
  EXPECT_FALSE(hex.closed_all_quads);
  EXPECT_EQ(hex.output.non_quads, 1);
}

}  // namespace
}  // namespace quadcover
