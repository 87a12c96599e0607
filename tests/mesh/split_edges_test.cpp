// Midpoint edge splits (mesh/split_edges.h): the refined triangulation covers the same surface with the same
// orientation and topology, keeps the input's vertices, and every new triangle is non-degenerate.
#include <gtest/gtest.h>

#include <stdexcept>

#include "mesh/split_edges.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// Checks the refinement of `mesh` by `edges` against a direct recomputation of area, normals and topology.
void expect_same_surface(const Mesh& mesh, const std::vector<int>& edges) {
  const SplitMesh split = split_edges_at_midpoints(mesh, edges);
  const Mesh refined = Mesh::from_triangles(split.V, split.F);
  ASSERT_EQ(refined.num_vertices(), mesh.num_vertices() + static_cast<int>(edges.size()));
  EXPECT_TRUE(split.V.topRows(mesh.num_vertices()) == mesh.V());
  // Each split edge adds one triangle per face beside it.
  int added = 0;
  for (int e : edges) added += (mesh.EF()(e, 0) >= 0) + (mesh.EF()(e, 1) >= 0);
  EXPECT_EQ(refined.num_faces(), mesh.num_faces() + added);
  EXPECT_EQ(refined.genus(), mesh.genus());
  EXPECT_EQ(refined.num_boundary_loops(), mesh.num_boundary_loops());
  EXPECT_EQ(refined.num_components(), mesh.num_components());
  // Per parent: the children's areas add up to its area and their normals are its normal.
  Eigen::VectorXd area = Eigen::VectorXd::Zero(mesh.num_faces());
  for (int t = 0; t < refined.num_faces(); ++t) {
    const int f = split.parent_face[t];
    area[f] += refined.face_areas()[t];
    EXPECT_GT(refined.face_areas()[t], 0.2 * mesh.face_areas()[f]) << "child " << t << " of face " << f;
    EXPECT_NEAR(refined.face_normals().row(t).dot(mesh.face_normals().row(f)), 1.0, 1e-12);
  }
  for (int f = 0; f < mesh.num_faces(); ++f) EXPECT_NEAR(area[f], mesh.face_areas()[f], 1e-12 * mesh.face_areas()[f]);
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Eigen::RowVector3d mid =
        0.5 * (mesh.V().row(mesh.E()(edges[k], 0)) + mesh.V().row(mesh.E()(edges[k], 1)));
    EXPECT_TRUE(split.V.row(mesh.num_vertices() + static_cast<Eigen::Index>(k)).isApprox(mid));
  }
}

TEST(SplitEdges, OneTwoOrThreeSplitEdgesPerFaceKeepTheSurface) {
  const Mesh grid = testing::make_grid(4);
  for (const std::vector<int>& edges :
       {std::vector<int>{grid.FE()(5, 0)}, std::vector<int>{grid.FE()(5, 0), grid.FE()(5, 1)},
        std::vector<int>{grid.FE()(5, 0), grid.FE()(5, 1), grid.FE()(5, 2)}})
    expect_same_surface(grid, edges);
}

TEST(SplitEdges, BoundaryAndInteriorEdgesOfAClosedAndAnOpenSurface) {
  const Mesh torus = testing::make_torus(8, 6);
  std::vector<int> every_third;
  for (int e = 0; e < torus.num_edges(); e += 3) every_third.push_back(e);
  expect_same_surface(torus, every_third);
  const Mesh cylinder = testing::make_cylinder(8, 3);
  std::vector<int> boundary;
  for (int e = 0; e < cylinder.num_edges(); ++e)
    if (cylinder.is_boundary_edge(e)) boundary.push_back(e);
  expect_same_surface(cylinder, boundary);
}

TEST(SplitEdges, ARepeatedOrUnknownEdgeIsRefused) {
  const Mesh grid = testing::make_grid(2);
  EXPECT_THROW(split_edges_at_midpoints(grid, {0, 0}), std::invalid_argument);
  EXPECT_THROW(split_edges_at_midpoints(grid, {grid.num_edges()}), std::invalid_argument);
}

}  // namespace
}  // namespace quadcover
