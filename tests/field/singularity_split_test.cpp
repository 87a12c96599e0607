// Splitting singularities of |quarter index| >= 2 into quarter-index branch points (field/singularity_split.h):
// the move plan, the matching changes it makes, and the whole field stage on a high-valence bipyramid.
#include "field/singularity_split.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "field/compute_frame_field.h"
#include "field/indices.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// The graph distance (edges) from v to w, by breadth-first search.
int hops(const Mesh& mesh, int v, int w) {
  std::vector<int> d(static_cast<std::size_t>(mesh.num_vertices()), -1), queue{v};
  d[static_cast<std::size_t>(v)] = 0;
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const int u = queue[i];
    if (u == w) return d[static_cast<std::size_t>(u)];
    for (int e = 0; e < mesh.num_edges(); ++e)
      for (int s = 0; s < 2; ++s)
        if (mesh.E()(e, s) == u && d[static_cast<std::size_t>(mesh.E()(e, 1 - s))] < 0) {
          d[static_cast<std::size_t>(mesh.E()(e, 1 - s))] = d[static_cast<std::size_t>(u)] + 1;
          queue.push_back(mesh.E()(e, 1 - s));
        }
  }
  return -1;
}

TEST(SingularitySplit, PlanMovesEveryQuarterToADistinctFreeVertexNearby) {
  const Mesh torus = testing::make_torus(24, 12);  // valence 6 everywhere
  const int a = 5 * 12 + 3, b = 17 * 12 + 8, blocked = 18 * 12 + 9;
  Eigen::VectorXi q = Eigen::VectorXi::Zero(torus.num_vertices());
  q[a] = 3;
  q[b] = -8;       // more quarters than the 1-ring has vertices: the 2-ring is used as well
  q[blocked] = 1;  // a neighbour of b that is a branch point already: not a target
  ASSERT_EQ(hops(torus, b, blocked), 1);
  const std::vector<QuarterMove> moves = plan_singularity_split(torus, q);
  ASSERT_EQ(moves.size(), 11u);
  Eigen::VectorXi after = q;
  std::set<int> targets;
  for (const QuarterMove& m : moves) {
    EXPECT_EQ(m.quarters, m.from == a ? 1 : -1);
    EXPECT_TRUE(targets.insert(m.to).second) << "vertex " << m.to << " chosen twice";
    EXPECT_EQ(q[m.to], 0);
    EXPECT_LE(hops(torus, m.from, m.to), m.from == a ? 1 : 2);
    after[m.from] -= m.quarters;
    after[m.to] += m.quarters;
  }
  EXPECT_EQ(after.sum(), q.sum());
  EXPECT_EQ(after.cwiseAbs().maxCoeff(), 1);
  EXPECT_EQ(after[a], 0);
  EXPECT_EQ(after[b], 0);
  EXPECT_EQ(after[blocked], 1);
  // Three quarters around a valence-6 vertex: evenly spread, every other ring vertex.
  std::vector<int> around_a;
  for (const QuarterMove& m : moves)
    if (m.from == a) around_a.push_back(m.to);
  for (std::size_t i = 0; i < around_a.size(); ++i)
    for (std::size_t j = i + 1; j < around_a.size(); ++j) EXPECT_EQ(hops(torus, around_a[i], around_a[j]), 2);

  // The matching changes move exactly these quarters of matching index (Def. 3.2), nothing else.
  Eigen::VectorXi matching = Eigen::VectorXi::Zero(torus.num_edges());
  EXPECT_GE(apply_quarter_moves(torus, moves, matching), 11);  // at least one edge per move
  EXPECT_EQ(matching_quarter_index(torus, matching), after - q);
  EXPECT_EQ(plan_singularity_split(torus, after).size(), 0u);  // nothing left to split
}

// Thesis 5.1 on a bipyramid whose apexes have valence 500: the smooth field is rotationally symmetric, with a
// whole-turn singularity (quarter index 4, a cone of angle 0 that folds the map) at each apex. The split leaves
// eight quarter-index branch points spread around the equator, and Σ = 4χ.
TEST(SingularitySplit, BipyramidApexesBecomeEightQuarterBranchPoints) {
  const int n = 500;
  const Mesh m = testing::make_fan(n, true);
  ASSERT_EQ(m.valence(0), n);
  FieldOptions no_split;
  no_split.split_singularities = false;
  const FrameFieldResult before = compute_frame_field_detailed(m, no_split);
  const Eigen::VectorXi q0 = cross_field_quarter_index(m, before.field);
  EXPECT_EQ(q0[0], 4);
  EXPECT_EQ(q0[n + 1], 4);
  EXPECT_EQ(q0.sum(), 4 * m.euler_characteristic());
  EXPECT_TRUE(before.branch_points.empty());  // index 1 does not branch the 4-sheeted cover
  EXPECT_TRUE(before.singularity_moves.empty());

  const FrameFieldResult after = compute_frame_field_detailed(m);
  const Eigen::VectorXi q = cross_field_quarter_index(m, after.field);
  EXPECT_EQ(q.sum(), 4 * m.euler_characteristic());  // Poincaré–Hopf
  EXPECT_EQ(q.cwiseAbs().maxCoeff(), 1);
  EXPECT_EQ(q[0], 0);
  EXPECT_EQ(q[n + 1], 0);
  EXPECT_EQ(after.singularity_moves.size(), 8u);
  ASSERT_EQ(after.branch_points.size(), 8u);
  double closest = 1e9;
  for (const BranchPoint& p : after.branch_points) {
    EXPECT_EQ(p.quarter_index, 1);
    EXPECT_EQ(m.V()(p.vertex, 2), 0.0);  // on the equator
    for (const BranchPoint& o : after.branch_points)
      if (o.vertex != p.vertex) closest = std::min(closest, (m.V().row(p.vertex) - m.V().row(o.vertex)).norm());
  }
  EXPECT_GT(closest, 0.7);  // 45° apart on the unit circle: chord 2 sin(π/8) = 0.765
  // The re-smoothed field is a cross field of finite energy, and still close to the curvature-free ideal.
  EXPECT_TRUE(after.field.X.allFinite());
  EXPECT_TRUE(std::isfinite(after.energy_smooth));
}

// Real meshes have no whole-turn singularity. cow has two vertices of quarter index 3 (and some of ±2),
// mech_holes_shark one of 2 (on its boundary, which the split leaves alone). The default (split_min_quarters = 2)
// splits every interior one into quarters and keeps Σ = 4χ; whole turns only (4) leaves them all.
TEST(SingularitySplit, DefaultSplitsHalfAndThreeQuarterConesOfRealMeshes) {
  for (const char* name : {"bunny_3k", "fandisk", "mech_holes_shark", "cow"}) {
    const Mesh m = testing::load_test_mesh(name);
    FieldOptions unsplit;
    unsplit.split_singularities = false;
    const Eigen::VectorXi q0 = cross_field_quarter_index(m, compute_frame_field_detailed(m, unsplit).field);
    const FrameFieldResult r = compute_frame_field_detailed(m);
    const Eigen::VectorXi q = cross_field_quarter_index(m, r.field);
    EXPECT_EQ(q.sum(), q0.sum()) << name;
    int interior_max = 0, interior_max0 = 0;
    for (int v = 0; v < m.num_vertices(); ++v)
      if (!m.is_boundary_vertex(v)) {
        interior_max = std::max(interior_max, std::abs(q(v)));
        interior_max0 = std::max(interior_max0, std::abs(q0(v)));
      }
    EXPECT_EQ(interior_max, std::min(interior_max0, 1)) << name;
    EXPECT_EQ(r.singularity_moves.empty(), interior_max0 < 2) << name;
    FieldOptions whole_turns;
    whole_turns.split_min_quarters = 4;
    EXPECT_TRUE(compute_frame_field_detailed(m, whole_turns).singularity_moves.empty()) << name;
    if (std::string(name) == "cow") {
      EXPECT_EQ(interior_max0, 3);
    }
  }
}

}  // namespace
}  // namespace quadcover
