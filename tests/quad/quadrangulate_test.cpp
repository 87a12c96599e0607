// Splitting / merging polygons into quads (quad/quadrangulate.h) on a known closed quad mesh: the extraction of the
// cube map (6·5² planar unit squares). Polygons made by removing edges must come back as the original quads.
#include "quad/quadrangulate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <set>

#include "quad/cube_quads.h"
#include "quad/extract_quads.h"
#include "quad/polygon_check.h"

namespace quadcover {
namespace {

using testing::cube_quads;
using testing::face_sets;

// Merges face f with the face across its side i (removes that edge); returns the index of the merged polygon.
int merge_across(QuadMesh& q, int f, int i) {
  const std::vector<int> F = q.faces[f];
  const int n = static_cast<int>(F.size()), a = F[i], b = F[(i + 1) % n];
  int g = -1;
  for (int h = 0; h < q.num_faces() && g < 0; ++h) {
    const auto& G = q.faces[h];
    for (std::size_t k = 0; k < G.size(); ++k)
      if (G[k] == b && G[(k + 1) % G.size()] == a) g = h;
  }
  EXPECT_GE(g, 0);
  const std::vector<int> G = q.faces[g];
  const int m = static_cast<int>(G.size());
  std::vector<int> merged;
  for (int k = 0; k < n; ++k) merged.push_back(F[(i + 1 + k) % n]);
  const int ja = static_cast<int>(std::find(G.begin(), G.end(), a) - G.begin());
  for (int k = 1; k < m - 1; ++k) merged.push_back(G[(ja + k) % m]);
  q.faces[f] = merged;
  q.faces.erase(q.faces.begin() + g);
  return g < f ? f - 1 : f;
}

void expect_closed_all_quad_sphere(const QuadMesh& q) {
  const testing::PolygonCheck c = testing::check_polygons(q.num_vertices(), q.faces);
  EXPECT_EQ(c.problems, 0);
  EXPECT_EQ(c.boundary_edges, 0);
  EXPECT_EQ(c.euler(), 2);
  EXPECT_EQ(q.num_quads(), q.num_faces());
}

// Hexagons (two squares without their shared edge) are split back along the missing edge: the only split with
// right angles (the other two diagonals give 45°/135° corners).
TEST(Quadrangulate, HexagonsSplitBackIntoTheSquares) {
  const QuadMesh original = cube_quads();
  QuadMesh q = original;
  for (int f : {0, 40, 80, 120}) merge_across(q, f, 1);
  ASSERT_EQ(q.num_faces(), 146);
  ASSERT_EQ(q.num_quads(), 142);
  const QuadrangulateReport r = quadrangulate_polygons(q);
  EXPECT_EQ(r.split_polygons, 4);
  EXPECT_EQ(r.merged_pairs, 0);
  expect_closed_all_quad_sphere(q);
  EXPECT_EQ(face_sets(q), face_sets(original));
}

// A square cut into two triangles by a diagonal: the odd pair is merged back into the square. A triangle next to a
// pentagon (two squares re-cut) is merged into a hexagon and split into two squares again.
TEST(Quadrangulate, OddPairsAreMergedAndSplit) {
  const QuadMesh original = cube_quads();
  QuadMesh q = original;
  {
    const std::vector<int> F = q.faces[7];
    q.faces[7] = {F[0], F[1], F[2]};
    q.faces.push_back({F[0], F[2], F[3]});
  }
  {
    const int h = merge_across(q, 60, 2);  // hexagon [b0..b5] from squares 60 and its neighbour
    const std::vector<int> H = q.faces[h];
    q.faces[h] = {H[0], H[1], H[2]};  // triangle + pentagon
    q.faces.push_back({H[0], H[2], H[3], H[4], H[5]});
  }
  const QuadrangulateReport r = quadrangulate_polygons(q);
  EXPECT_EQ(r.merged_pairs, 2);
  EXPECT_EQ(r.split_polygons, 1);
  expect_closed_all_quad_sphere(q);
  EXPECT_EQ(q.num_faces(), 150);
  EXPECT_EQ(face_sets(q), face_sets(original));
}

// A polygon with a side on a boundary (here a hole next to it) is a clipped cell and stays as it is.
TEST(Quadrangulate, LeavesBoundaryPolygonsAlone) {
  QuadMesh q = cube_quads();
  const int h = merge_across(q, 10, 1);
  const std::vector<int> H = q.faces[h];
  int across = -1;  // the face across the hexagon's side H0-H1
  for (int f = 0; f < q.num_faces(); ++f)
    for (std::size_t k = 0; k < q.faces[f].size(); ++k)
      if (q.faces[f][k] == H[1] && q.faces[f][(k + 1) % q.faces[f].size()] == H[0]) across = f;
  ASSERT_GE(across, 0);
  q.faces.erase(q.faces.begin() + across);
  const QuadrangulateReport r = quadrangulate_polygons(q);
  EXPECT_EQ(r.split_polygons, 0);
  EXPECT_EQ(std::count_if(q.faces.begin(), q.faces.end(), [](const auto& f) { return f.size() == 6; }), 1);
  const testing::PolygonCheck c = testing::check_polygons(q.num_vertices(), q.faces);
  EXPECT_EQ(c.problems, 0);
  EXPECT_EQ(c.boundary_loops, 1);
}

// A triangle (c, x, g) with its side c–x on the boundary between two quads: c and x become one boundary vertex at
// the midpoint the caller gives, the quads beside it stay quads; a midpoint that would fold a quad over is refused.
TEST(Quadrangulate, BoundarySideOfATriangleIsCollapsed) {
  QuadMesh q;
  q.V.resize(8, 3);
  q.V << -1, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0, -1, 1, 0, 0.5, 0.8, 0, 2, 1, 0, 0.5, 2, 0;
  enum { b0, c, x, b3, u0, g, u3, t };
  q.faces = {{b0, c, g, u0}, {c, x, g}, {x, b3, u3, g}, {u0, g, u3, t}};
  q.uv = Eigen::VectorXcd::Zero(8);
  q.source_face = Eigen::VectorXi::Zero(8);
  q.on_grid = Eigen::VectorXi::Zero(8);
  const auto at = [](double px) {
    return [px](const Eigen::Vector3d&, const Eigen::Vector3d&) {
      return std::optional<BoundaryPoint>(BoundaryPoint{Eigen::Vector3d(px, 0, 0), 7, {px, 0}});
    };
  };
  QuadMesh folding = q;
  EXPECT_EQ(collapse_boundary_sides(folding, at(5.0)), 0);  // x past b3: the right quad would fold over
  EXPECT_EQ(folding.faces, q.faces);
  EXPECT_EQ(collapse_boundary_sides(q, at(0.5)), 1);
  EXPECT_EQ(q.num_faces(), 3);
  EXPECT_EQ(q.num_quads(), 3);
  EXPECT_EQ(q.V.row(c), Eigen::RowVector3d(0.5, 0, 0));
  EXPECT_EQ(q.source_face[c], 7);
  const testing::PolygonCheck check = testing::check_polygons(q.num_vertices(), q.faces);
  EXPECT_EQ(check.problems, 0);
  EXPECT_EQ(check.unreferenced, 1);  // x
  EXPECT_EQ(check.euler(), 1);
  EXPECT_EQ(check.boundary_loops, 1);
  for (const auto& f : q.faces) EXPECT_EQ(std::count(f.begin(), f.end(), x), 0);
}

// Holes: removing two adjacent squares leaves a hexagonal hole; closing it gives a hexagon face that is split back
// into the squares. A loop longer than max_loop, or one the predicate refuses, stays open.
TEST(Quadrangulate, SmallHolesAreClosedAndSplit) {
  const QuadMesh original = cube_quads();
  QuadMesh q = original;
  const int h = merge_across(q, 33, 0);
  q.faces.erase(q.faces.begin() + h);  // a hole with 6 boundary edges
  QuadMesh refused = q, too_long = q;
  EXPECT_EQ(fill_small_holes(refused, 8, [](const std::vector<int>&) { return false; }), 0);
  EXPECT_EQ(fill_small_holes(too_long, 5, [](const std::vector<int>&) { return true; }), 0);
  EXPECT_EQ(refused.num_faces(), q.num_faces());
  EXPECT_EQ(too_long.num_faces(), q.num_faces());
  std::vector<int> seen_loop;
  EXPECT_EQ(fill_small_holes(q, 8, [&](const std::vector<int>& loop) {
              seen_loop = loop;
              return true;
            }),
            1);
  EXPECT_EQ(seen_loop.size(), 6u);
  const QuadrangulateReport r = quadrangulate_polygons(q);
  EXPECT_EQ(r.split_polygons, 1);
  expect_closed_all_quad_sphere(q);
  EXPECT_EQ(face_sets(q), face_sets(original));
}

}  // namespace
}  // namespace quadcover
