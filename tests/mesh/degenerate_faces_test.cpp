// Zero-area triangles removed for `quadcover repair` (mesh/degenerate_faces.h), on small soups whose answer is known.
#include "mesh/degenerate_faces.h"

#include <gtest/gtest.h>

#include "mesh/mesh.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

PolygonSoup polygon_soup(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces) {
  return PolygonSoup::from_polygons(V, faces);
}

double area_of(const Mesh& m) { return m.face_areas().sum(); }

// The unit square (0, 1, 2), (0, 2, 3) and the triangle 1, 5, 2 beside it, split at 4, the midpoint of 1–2, into
// (1, 5, 4), (4, 5, 2); the cap (4, 2, 1) closes the crack along 1–2. Flipping 1–2 to 4–0 splits (0, 1, 2) at 4.
TEST(DegenerateFaces, ACapIsFlippedAwayAndTheSurfaceIsTheSame) {
  Eigen::MatrixX3d V(6, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0.5, 0, 2, 0.5, 0;
  PolygonSoup soup = polygon_soup(V, {{0, 1, 2}, {0, 2, 3}, {4, 2, 1}, {1, 5, 4}, {4, 5, 2}});
  EXPECT_THROW(build_mesh(soup), TopologyError);
  const DegenerateFaceRemoval r = remove_degenerate_faces(soup, ValidationOptions{}.degenerate_tolerance);
  EXPECT_EQ(r.flipped_caps, 1u);
  EXPECT_EQ(r.total(), 1u);
  ASSERT_EQ(soup.num_faces(), 5u);
  const MeshBuildResult built = build_mesh(soup);
  EXPECT_TRUE(built.report.valid());
  EXPECT_NEAR(area_of(built.mesh), 1.0 + 0.5, 1e-12);
  EXPECT_GT(built.mesh.face_areas().minCoeff(), 0.2);
  EXPECT_EQ(built.mesh.euler_characteristic(), 1);
  EXPECT_EQ(built.mesh.num_boundary_loops(), 1);
}

TEST(DegenerateFaces, ACapOnTheBoundaryIsDropped) {
  Eigen::MatrixX3d V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 0, 0, 0.5, 1, 0;
  PolygonSoup soup =
      polygon_soup(V, {{0, 2, 3}, {2, 1, 3}, {0, 1, 2}});  // (0, 1, 2) is flat, its edge 0–1 on the boundary
  const DegenerateFaceRemoval r = remove_degenerate_faces(soup, 1e-12);
  EXPECT_EQ(r.boundary_caps, 1);
  ASSERT_EQ(soup.num_faces(), 2u);
  const Mesh m = build_mesh(soup).mesh;
  EXPECT_NEAR(area_of(m), 0.5, 1e-12);
  EXPECT_EQ(m.num_boundary_loops(), 1);
}

// A torus grid with one vertex doubled (same position, new index) on one triangle: the needle (v, v', w) and its
// neighbour across v–v' go, v' merges into v, and the torus comes back.
TEST(DegenerateFaces, TwoCornersAtOnePointAreMerged) {
  const Mesh torus = testing::make_torus(12, 8);
  Eigen::MatrixX3d V(torus.num_vertices() + 1, 3);
  V << torus.V(), torus.V().row(0);
  const int twin = torus.num_vertices();
  std::vector<std::vector<int>> faces;
  for (int f = 0; f < torus.num_faces(); ++f) faces.push_back({torus.F()(f, 0), torus.F()(f, 1), torus.F()(f, 2)});
  // Vertex 0's first face (0, a, b) takes the twin for its corner 0; two needles close the gap: (0, a, twin) and
  // (0, twin, b).
  auto& f0 = faces[static_cast<std::size_t>(torus.fan(0)[0].face)];
  const int k = static_cast<int>(std::find(f0.begin(), f0.end(), 0) - f0.begin());
  const int a = f0[(k + 1) % 3], b = f0[(k + 2) % 3];
  f0[static_cast<std::size_t>(k)] = twin;
  faces.push_back({0, a, twin});
  faces.push_back({0, twin, b});
  PolygonSoup soup = polygon_soup(V, faces);
  EXPECT_THROW(build_mesh(soup), TopologyError);
  const DegenerateFaceRemoval r = remove_degenerate_faces(soup, 1e-12);
  EXPECT_GE(r.merged_needles, 1u);
  const MeshBuildResult built = build_mesh(soup);
  EXPECT_TRUE(built.report.valid());
  EXPECT_EQ(built.mesh.num_faces(), torus.num_faces());
  EXPECT_EQ(built.mesh.genus(), 1);
  EXPECT_NEAR(area_of(built.mesh), area_of(torus), 1e-12);
}

TEST(DegenerateFaces, RepeatedVerticesAndRepeatedFacesAreDroppedAndNothingElseChanges) {
  const Mesh sphere = testing::make_ellipsoid(1);
  std::vector<std::vector<int>> faces;
  for (int f = 0; f < sphere.num_faces(); ++f) faces.push_back({sphere.F()(f, 0), sphere.F()(f, 1), sphere.F()(f, 2)});
  PolygonSoup clean = polygon_soup(sphere.V(), faces);
  EXPECT_EQ(remove_degenerate_faces(clean, 1e-12).total(), 0u);
  EXPECT_EQ(clean.num_faces(), faces.size());
  faces.push_back({3, 3, 5});
  faces.push_back({faces[7][1], faces[7][2], faces[7][0]});
  PolygonSoup soup = polygon_soup(sphere.V(), faces);
  const DegenerateFaceRemoval r = remove_degenerate_faces(soup, 1e-12);
  EXPECT_EQ(r.repeated_vertex, 1u);
  EXPECT_EQ(r.duplicates, 1u);
  EXPECT_EQ(soup.num_faces(), static_cast<std::size_t>(sphere.num_faces()));
  EXPECT_TRUE(build_mesh(soup).report.valid());
}

}  // namespace
}  // namespace quadcover
