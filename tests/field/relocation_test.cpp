// Branch point relocation (thesis 5.2.2).
#include "field/relocation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "field/indices.h"
#include "field/matching.h"
#include "field/propagation.h"
#include "field/smoothing.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// Moves a branch point of a smoothed curvature field on a real mesh to a regular vertex several edges away:
// the matching changes only on the path, by exactly 4·ind(p); the matching index moves from p to q and stays at
// every other vertex; after the re-solve (two triangular solves) the branch points of the field are the old
// ones with p replaced by q, with q carrying p's index class.
TEST(Relocation, MovesExactlyOneBranchPoint) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const CurvatureFrames frames = principal_curvature_frames(mesh);
  const Eigen::VectorXd theta = field_curvature(mesh, cross_field_with_straightest_matching(mesh, frames.direction));
  const Eigen::VectorXd w = stability_weights(mesh, frames, theta);
  const std::vector<char> trusted = select_trusted(mesh, w, 0.2);
  const FrameField start =
      cross_field_with_straightest_matching(mesh, propagate_frames(mesh, frames.direction, trusted, w));
  FrameSmoother smoother(mesh, start, w, trusted, {}, 0.5);
  const FrameField smoothed = smoother.rotated(smoother.solve());
  const std::vector<BranchPoint> before = branch_points(mesh, smoothed);
  ASSERT_FALSE(before.empty());
  std::set<int> singular;
  for (const auto& b : before) singular.insert(b.vertex);

  // p: the first branch point; q: a vertex at least 5 edges away whose path avoids other branch points.
  const int p = before.front().vertex;
  int q = -1;
  std::vector<int> path;
  for (int v = 0; v < mesh.num_vertices() && q < 0; ++v) {
    if (singular.count(v) || mesh.is_boundary_vertex(v)) continue;
    const std::vector<int> candidate = relocation_path(mesh, p, v);
    if (candidate.size() < 6) continue;
    if (std::any_of(candidate.begin() + 1, candidate.end(), [&](int x) { return singular.count(x) > 0; })) continue;
    q = v;
    path = candidate;
  }
  ASSERT_GE(q, 0);

  const Eigen::VectorXi match_before = matching_quarter_index(mesh, smoothed.matching);
  Eigen::VectorXi matching = smoothed.matching;
  const std::vector<MatchingChange> changes = relocate_branch_point(mesh, matching, p, q);
  ASSERT_EQ(changes.size(), path.size() - 1);
  std::set<int> path_edges;
  for (const auto& c : changes) {
    EXPECT_EQ(std::abs(c.delta), std::abs(match_before[p]));
    path_edges.insert(c.edge);
  }
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!path_edges.count(e)) {
      ASSERT_EQ(matching[e], smoothed.matching[e]) << "edge " << e;
    }

  const Eigen::VectorXi match_after = matching_quarter_index(mesh, matching);
  EXPECT_EQ(match_after[p], 0);
  EXPECT_EQ(match_after[q], match_before[q] + match_before[p]);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (v != p && v != q) {
      ASSERT_EQ(match_after[v], match_before[v]) << "vertex " << v;
    }

  for (const auto& c : changes) smoother.change_matching(c.edge, c.delta);
  ASSERT_EQ(smoother.matching(), matching);
  const FrameField moved = smoother.rotated(smoother.solve());
  const std::vector<BranchPoint> after = branch_points(mesh, moved);
  std::set<int> expected = singular;
  expected.erase(p);
  expected.insert(q);
  std::set<int> got;
  for (const auto& b : after) got.insert(b.vertex);
  EXPECT_EQ(got, expected);
  for (const auto& b : after)
    if (b.vertex == q) {
      EXPECT_EQ(((b.quarter_index - before.front().quarter_index) % 4 + 4) % 4, 0);
    }
  EXPECT_EQ(cross_field_quarter_index(mesh, moved).sum(), 4 * mesh.euler_characteristic());
}

// Path properties: starts at p, ends at q, consecutive vertices share an interior edge, no boundary vertex
// inside; a boundary p is rejected.
TEST(Relocation, PathThroughInteriorEdges) {
  const Mesh mesh = testing::load_test_mesh("lilium_disk");
  int p = 0;
  while (mesh.is_boundary_vertex(p)) ++p;
  const int q = mesh.boundary_loops()[0][0];
  const std::vector<int> path = relocation_path(mesh, p, q);
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path.front(), p);
  EXPECT_EQ(path.back(), q);
  for (std::size_t i = 1; i + 1 < path.size(); ++i) EXPECT_FALSE(mesh.is_boundary_vertex(path[i]));
  const auto changes = relocation_changes(mesh, path, 2);
  for (const auto& c : changes) EXPECT_FALSE(mesh.is_boundary_edge(c.edge));
  EXPECT_THROW(relocation_path(mesh, q, p), std::invalid_argument);
}

}  // namespace
}  // namespace quadcover
