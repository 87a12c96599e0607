// The cut through B and the gauge (thesis 4.2) on real and generated meshes with many close branch points: the
// gauged matching is m' = m + r_s − r_t and ≡ 0 mod 4 off the cut, the transitions are k_e = −m'_e mod 4, the branch
// points are the vertices of non-zero matching index (recomputed; Def. 3.2, whose sum over a closed mesh is 0),
// the cut mesh is one disk per component (χ = 1 each) and h_sym is (4.1).
#include "param/cover_cut.h"

#include <gtest/gtest.h>

#include "cover/field_helpers.h"
#include "field/compute_frame_field.h"
#include "field/indices.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

int mod4(int k) { return ((k % 4) + 4) % 4; }

void check_cut(const Mesh& mesh, const Eigen::VectorXi& matching, const std::string& name) {
  SCOPED_TRACE(name);
  const CoverCut cc = build_cover_cut(mesh, matching);
  const int ne = mesh.num_edges(), nv = mesh.num_vertices();
  ASSERT_EQ(cc.matching.size(), ne);
  ASSERT_EQ(cc.face_rotation.size(), mesh.num_faces());
  for (int e = 0; e < ne; ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    EXPECT_EQ(cc.matching[e], matching[e] + cc.face_rotation[s] - cc.face_rotation[t]) << "edge " << e;
    if (!cc.graph.cut[e]) {
      EXPECT_EQ(mod4(cc.matching[e]), 0) << "uncut edge " << e;
      EXPECT_EQ(cc.rotation[e], 0) << "uncut edge " << e;
    } else {
      EXPECT_EQ(mod4(cc.rotation[e]), mod4(-cc.matching[e])) << "cut edge " << e;
    }
  }
  // Branch points: the vertices of non-zero matching index, recomputed from the input matching (the gauge does not
  // change the sum of the matching around a vertex).
  const Eigen::VectorXi q = matching_quarter_index(mesh, matching);
  int b_even = 0, b_odd = 0, sum = 0;
  for (int v = 0; v < nv; ++v) {
    EXPECT_EQ(cc.quarter_index[v], q[v]) << "vertex " << v;
    const bool branch = !mesh.is_boundary_vertex(v) && mod4(q[v]) != 0;
    EXPECT_EQ(cc.branch[v] != 0, branch) << "vertex " << v;
    if (branch) (mod4(q[v]) == 2 ? b_even : b_odd) += 1;
    sum += q[v];
  }
  EXPECT_EQ(cc.b_even, b_even);
  EXPECT_EQ(cc.b_odd, b_odd);
  // Σ_v Σ_{e∋v} ±m_e: every interior edge is counted at both endpoints with opposite signs.
  if (mesh.num_boundary_loops() == 0) {
    EXPECT_EQ(sum, 0);
  }
  // One topological disk per component: V − E + F = 1 on each.
  EXPECT_EQ(cc.disk.num_pieces, mesh.num_components());
  EXPECT_EQ(cc.disk.num_vertices() - cc.disk.num_edges + mesh.num_faces(), mesh.num_components());
  for (const auto& loop : cc.disk.boundary_loops) EXPECT_FALSE(loop.empty());
  EXPECT_EQ(cc.disk.boundary_loops.size(), static_cast<std::size_t>(mesh.num_components()));
  // The paths: their leftover edges are cut edges, and h_sym is (4.1) per component (one component here).
  ASSERT_EQ(cc.path_edge.size(), cc.path_component.size());
  for (int e : cc.path_edge) EXPECT_TRUE(cc.graph.cut[e]);
  if (mesh.num_components() == 1) {
    EXPECT_EQ(cc.h_sym(), symmetric_period_count(mesh.genus(), b_even, b_odd, mesh.num_boundary_loops()));
  }
}

TEST(CoverCut, GaugeTransitionsBranchPointsAndDisksOnRealMeshes) {
  for (const char* name : {"eight_genus2", "lilium_disk", "3holes_genus3", "mech_holes_shark"}) {
    const Mesh mesh = testing::load_test_mesh(name);
    check_cut(mesh, compute_frame_field(mesh).matching, name);
  }
}

TEST(CoverCut, GaugeTransitionsBranchPointsAndDisksWithManyCloseCones) {
  // Random cross fields: branch points on neighbouring vertices everywhere, on a coarse torus and a cylinder
  // (boundary) and a thin ellipsoid (slivers).
  const Mesh meshes[] = {testing::make_torus(12, 6), testing::make_cylinder(10, 4),
                         testing::make_ellipsoid(2, 1.0, 0.2, 0.05)};
  int k = 0;
  for (const Mesh& mesh : meshes)
    for (unsigned seed : {1u, 5u})
      check_cut(mesh, testing::random_cross_field(mesh, seed).matching, std::to_string(k++));
}

TEST(CoverCut, FanCrossingsWalkAroundEachVertex) {
  const Mesh mesh = testing::load_test_mesh("lilium_disk");
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const std::vector<FanCrossing> fan = fan_crossings(mesh, v);
    const int faces = static_cast<int>(mesh.fan(v).size());
    ASSERT_EQ(static_cast<int>(fan.size()), mesh.is_boundary_vertex(v) ? faces - 1 : faces) << v;
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const FanCrossing& x = fan[i];
      EXPECT_EQ(mesh.EF()(x.edge, 0) == x.from ? mesh.EF()(x.edge, 1) : mesh.EF()(x.edge, 0), x.to);
      EXPECT_TRUE(mesh.E()(x.edge, 0) == v || mesh.E()(x.edge, 1) == v);
      if (i + 1 < fan.size()) {
        EXPECT_EQ(x.to, fan[i + 1].from);
      }
    }
    if (!mesh.is_boundary_vertex(v) && !fan.empty()) {
      EXPECT_EQ(fan.back().to, fan.front().from);
    }
  }
}

TEST(CoverCut, TurnFrameIsMultiplicationByTheFrameComplexI) {
  const Complex X(0.3, -1.2), Y(2.0, 0.5);
  EXPECT_EQ(turn_frame(X, Y, 1), std::make_pair(-Y, X));
  for (int k = -5; k <= 5; ++k) {
    auto [a, b] = turn_frame(X, Y, k);
    std::tie(a, b) = turn_frame(a, b, 4 - mod4(k));  // i^k · i^(4−k) = 1
    EXPECT_EQ(a, X) << k;
    EXPECT_EQ(b, Y) << k;
  }
}

}  // namespace
}  // namespace quadcover
