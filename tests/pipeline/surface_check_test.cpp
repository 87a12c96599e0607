// check_surface: the counts of a polygon mesh against direct constructions, and every kind of difference named.
#include "pipeline/surface_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

// The places of the differences: the hexagon by its 1-based number and centroid, the cut-out face's hole as a
// boundary loop of 4 edges around that face's centroid; the warnings name them.
TEST(SurfaceCheck, PlacesNameTheNonQuadFacesAndTheNewHoles) {
  const Mesh torus = testing::make_torus(16, 8);
  Eigen::MatrixX3d V(48, 3);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 8; ++i) {
      const double a = 2 * M_PI * i / 8, b = 2 * M_PI * j / 6, r = 2 + 0.7 * std::cos(b);
      V.row(j * 8 + i) << r * std::cos(a), r * std::sin(a), 0.7 * std::sin(b);
    }
  auto faces = quad_grid(8, 6, true);
  const std::vector<int> cut = faces[20];
  faces.erase(faces.begin() + 20);
  faces[0] = {0, 1, 2, 10, 9, 8};
  faces.erase(faces.begin() + 1);
  SurfaceCheck check = check_surface(torus, 48, faces);
  locate_surface_problems(V, faces, check);
  ASSERT_EQ(check.places.size(), 2u);
  EXPECT_EQ(check.places[0].kind, "non-quad face");
  EXPECT_EQ(check.places[0].face, 1);
  EXPECT_EQ(check.places[0].size, 6);
  Eigen::Vector3d hexagon = Eigen::Vector3d::Zero(), hole = Eigen::Vector3d::Zero();
  for (int v : faces[0]) hexagon += V.row(v).transpose() / 6;
  for (int v : cut) hole += V.row(v).transpose() / 4;
  EXPECT_LT((check.places[0].at - hexagon).norm(), 1e-12);
  EXPECT_EQ(check.places[1].kind, "boundary loop");
  EXPECT_EQ(check.places[1].size, 4);
  EXPECT_LT((check.places[1].at - hole).norm(), 1e-12);
  const auto w = remesh_warnings(check, ExtractionReport{});
  EXPECT_TRUE(std::any_of(w.begin(), w.end(), [](const std::string& s) {
    return s.rfind("where: non-quad face 1 (6 sides) at (", 0) == 0 && s.find("boundary loop (4 edges)") != std::string::npos;
  }));
  // A clean result has no places and no such sentence.
  SurfaceCheck same = check_surface(torus, 48, quad_grid(8, 6, true));
  locate_surface_problems(V, quad_grid(8, 6, true), same);
  EXPECT_TRUE(same.places.empty());
}

TEST(SurfaceCheck, PinchedVerticesInconsistentFacesAndPolygons) {
  // Two quad squares sharing one corner (a bow-tie): one component, two boundary loops (one per fan), one
  // non-manifold vertex, genus undefined.
  auto faces = quad_grid(2, 2, false);
  for (auto f : quad_grid(2, 2, false)) {
    for (int& v : f) v = v == 0 ? 8 : v + 8;  // its corner vertex 0 is the first square's vertex 8
    faces.push_back(f);
  }
  const SurfaceCounts bow = surface_counts(17, faces);
  EXPECT_EQ(bow.components, 1);
  EXPECT_EQ(bow.boundary_loops, 2);
  EXPECT_EQ(bow.non_manifold_vertices, 1);
  EXPECT_EQ(bow.non_manifold_edges, 0);
  EXPECT_FALSE(bow.manifold());
  EXPECT_EQ(bow.genus, -1);
  EXPECT_EQ(bow.isolated_vertices, 0);
  // One face of a torus reversed: still a manifold of genus 1, but 4 edges disagree in orientation.
  auto flipped = quad_grid(8, 6, true);
  std::reverse(flipped[7].begin(), flipped[7].end());
  const SurfaceCounts f = surface_counts(48, flipped);
  EXPECT_TRUE(f.manifold());
  EXPECT_FALSE(f.oriented());
  EXPECT_EQ(f.inconsistent_edges, 4);
  EXPECT_EQ(f.genus, -1);
  EXPECT_EQ(surface_counts(48, quad_grid(8, 6, true)).genus, 1);
  // A fin: a third quad on an edge of the square grid, and a face with a repeated corner.
  auto fin = quad_grid(2, 2, false);
  fin.push_back({1, 4, 10, 9});  // on the interior edge (1, 4) of the first two quads
  const SurfaceCounts nm = surface_counts(11, fin);
  EXPECT_EQ(nm.non_manifold_edges, 1);
  EXPECT_FALSE(nm.manifold());
  auto repeated = quad_grid(2, 2, false);
  repeated.push_back({2, 5, 2, 9});
  EXPECT_EQ(surface_counts(10, repeated).degenerate_faces, 1);
  // A triangle mesh counted as polygons is the Mesh's own topology.
  const Mesh torus = testing::make_torus(16, 8);
  const SurfaceCounts t = surface_counts(torus);
  EXPECT_EQ(t.genus, torus.genus());
  EXPECT_EQ(t.edges, torus.num_edges());
  EXPECT_EQ(t.non_quads, torus.num_faces());
}

TEST(SurfaceCheck, RemeshWarningsSayEveryDegradation) {
  const Mesh torus = testing::make_torus(16, 8);
  ExtractionReport clean;
  EXPECT_TRUE(remesh_warnings(check_surface(torus, 48, quad_grid(8, 6, true)), clean).empty());
  ExtractionReport repaired;
  repaired.moved_vertices = 3;
  repaired.torn_seams = 1;
  repaired.filled_holes = 1;
  const auto w = remesh_warnings(check_surface(torus, 48, quad_grid(8, 6, true)), repaired);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("3 vertices moved by the fold repair, 1 torn seam treated as boundary, 1 hole filled"),
            std::string::npos)
      << w[0];
  // Boundary slivers cut off are said on their own, not as a repair of the map; a degenerate face is a repair.
  ExtractionReport slivers;
  slivers.boundary_slivers = 2;
  const auto ws = remesh_warnings(check_surface(torus, 48, quad_grid(8, 6, true)), slivers);
  ASSERT_EQ(ws.size(), 1u);
  EXPECT_EQ(ws[0].find("2 slivers between the boundary and an iso-line it crosses twice cut off"), 0u) << ws[0];
  slivers.degenerate_faces = 1;
  const auto wd = remesh_warnings(check_surface(torus, 48, quad_grid(8, 6, true)), slivers);
  ASSERT_EQ(wd.size(), 2u);
  EXPECT_NE(wd[0].find("the extraction repaired the map (1 degenerate face dropped)"), std::string::npos) << wd[0];
  // A closed input with a hexagon: the check's problem, flagged, once.
  auto merged = quad_grid(8, 6, true);
  merged[0] = {0, 1, 2, 10, 9, 8};
  merged.erase(merged.begin() + 1);
  const SurfaceCheck hex = check_surface(torus, 48, merged);
  EXPECT_FALSE(hex.closed_all_quads);
  const auto wh = remesh_warnings(hex, clean);
  ASSERT_EQ(wh.size(), 1u);
  EXPECT_EQ(wh[0], "remesh changed the surface: the input is closed but 1 faces are not quads");
  // An open input with a hexagon: not a change of the surface, but still said.
  const Mesh grid = testing::make_grid(8);
  auto open = quad_grid(8, 6, false);
  open[0] = {0, 1, 2, 11, 10, 9};
  open.erase(open.begin() + 1);
  const auto wo = remesh_warnings(check_surface(grid, 63, open), clean);
  ASSERT_FALSE(wo.empty());
  EXPECT_EQ(wo.back(), "1 of the 47 faces are not quads");
}

}  // namespace
}  // namespace quadcover
