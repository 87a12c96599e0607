// Doublet removal (quad/doublets.h) on the extraction of the cube map (6·5² unit squares): doublets made by
// splitting a quad around a new vertex must go, giving back the original quads, and nothing else may change.
#include "quad/doublets.h"

#include <gtest/gtest.h>

#include <set>

#include "quad/cube_quads.h"
#include "quad/extract_quads.h"
#include "quad/polygon_check.h"

namespace quadcover {
namespace {

using testing::cube_quads;
using testing::face_sets;

// A new vertex at the centre of face f (its per-vertex data copied from the face's first corner).
int add_centre(QuadMesh& q, int f) {
  const int v = q.num_vertices();
  q.V.conservativeResize(v + 1, 3);
  q.V.row(v).setZero();
  for (int c : q.faces[f]) q.V.row(v) += q.V.row(c) / static_cast<double>(q.faces[f].size());
  q.uv.conservativeResize(v + 1);
  q.uv[v] = q.uv[q.faces[f][0]];
  q.source_face.conservativeResize(v + 1);
  q.source_face[v] = q.source_face[q.faces[f][0]];
  q.on_grid.conservativeResize(v + 1);
  q.on_grid[v] = 0;
  return v;
}

void expect_closed_sphere(const QuadMesh& q) {
  const testing::PolygonCheck c = testing::check_polygons(q.num_vertices(), q.faces);
  EXPECT_EQ(c.problems, 0);
  EXPECT_EQ(c.boundary_edges, 0);
  EXPECT_EQ(c.euler(), 2);  // removed vertices stay as unused rows (not counted)
}

// Quad (a, b, c, d) split at a new vertex v into (a, b, c, v) and (c, d, a, v): v has valence 2.
TEST(Doublets, TwoQuadsAroundAValence2VertexBecomeTheQuadAgain) {
  QuadMesh q = cube_quads();
  const auto original = face_sets(q);
  for (const int f : {7, 80}) {
    const std::vector<int> Q = q.faces[f];
    const int v = add_centre(q, f);
    q.faces[f] = {Q[0], Q[1], Q[2], v};
    q.faces.push_back({Q[2], Q[3], Q[0], v});
  }
  expect_closed_sphere(q);
  ASSERT_EQ(q.num_faces(), 152);
  EXPECT_EQ(remove_doublets(q), 2);
  EXPECT_EQ(face_sets(q), original);
  EXPECT_EQ(q.num_quads(), 150);
  expect_closed_sphere(q);
  EXPECT_EQ(remove_doublets(q), 0);  // nothing left to do
}

// Where the doublet's vertex stands far off the union (the tip of a horn, which two faces folded round it hold),
// merging would cut the tip off: that doublet stays, a flat one goes.
TEST(Doublets, AVertexCarryingATipStays) {
  QuadMesh q = cube_quads();
  std::vector<int> centres;
  for (const int f : {7, 80}) {
    const std::vector<int> Q = q.faces[f];
    const int v = add_centre(q, f);
    q.faces[f] = {Q[0], Q[1], Q[2], v};
    q.faces.push_back({Q[2], Q[3], Q[0], v});
    centres.push_back(v);
  }
  const Eigen::Vector3d middle(0.5, 0.5, 0.5), at = q.V.row(centres[0]).transpose();  // the unit cube, quads of 0.2
  q.V.row(centres[0]) = (at + 0.5 * (at - middle).normalized()).transpose();          // a spike of 2.5 quad sides
  EXPECT_EQ(remove_doublets(q), 1);
  EXPECT_EQ(q.num_faces(), 151);
  std::vector<int> faces_at(static_cast<std::size_t>(q.num_vertices()), 0);
  for (const auto& f : q.faces)
    for (int v : f) ++faces_at[v];
  EXPECT_EQ(faces_at[centres[0]], 2);
  EXPECT_EQ(faces_at[centres[1]], 0);
  EXPECT_EQ(remove_doublets(q, 1e9), 1);  // with no limit it goes as well
}

// A hexagon (a, b, c, d, v2, v1) and a quad flap (a, v1, v2, d) sharing the chain a–v1–v2–d: both chain vertices
// go and the hexagon becomes the quad it was cut from (as extraction leaves it beside a wrongly wound branch point).
TEST(Doublets, AChainOfValence2VerticesGoesWithIt) {
  QuadMesh q = cube_quads();
  const auto original = face_sets(q);
  const int f = 42;
  const std::vector<int> Q = q.faces[f];
  const int v1 = add_centre(q, f), v2 = add_centre(q, f);
  q.faces[f] = {Q[0], Q[1], Q[2], Q[3], v2, v1};
  q.faces.push_back({Q[0], v1, v2, Q[3]});
  expect_closed_sphere(q);
  EXPECT_EQ(remove_doublets(q), 2);
  EXPECT_EQ(face_sets(q), original);
  expect_closed_sphere(q);
}

// Vertices of valence 2 on the boundary are corners of the patch, not doublets; and a doublet whose union would be
// no quad is kept rather than turning two quads into another polygon.
TEST(Doublets, BoundaryCornersAndUnmergeablePairsStay) {
  QuadMesh q = cube_quads();
  q.faces.erase(q.faces.begin() + 10);  // a hole: its four corners keep three faces each
  const auto open = face_sets(q);
  EXPECT_EQ(remove_doublets(q), 0);
  EXPECT_EQ(face_sets(q), open);
  // Two faces (a, b, v) and (b, a, v)... a triangle pair around v would merge into two corners: kept.
  QuadMesh t;
  t.V = Eigen::MatrixX3d::Zero(3, 3);
  t.faces = {{0, 1, 2}, {1, 0, 2}};
  EXPECT_EQ(remove_doublets(t), 0);
  EXPECT_EQ(t.num_faces(), 2);
}

}  // namespace
}  // namespace quadcover
