// Alignment to boundaries and sharp features, through the whole pipeline (compute_frame_field).
#include "field/feature_alignment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "common/union_find.h"
#include "field/compute_frame_field.h"
#include "mesh/shape_operator.h"
#include "mesh/split_edges.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// Given features (FeatureOptions::given): on a flat grid, whose dihedral angles are all 0, the given edges are the
// sharp ones and constrain their faces; after a midpoint split of one of them, both halves still are.
TEST(GivenFeatures, FlatEdgesGivenAreFollowedAndKeptThroughSplits) {
  const Mesh grid = testing::make_grid(6);
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> expected;
  for (int e = 0; e < grid.num_edges(); ++e) {  // the interior edges on the line y = 0.5
    const Eigen::Vector3d a = grid.V().row(grid.E()(e, 0)), b = grid.V().row(grid.E()(e, 1));
    if (!grid.is_boundary_edge(e) && std::abs(a.y() - 0.5) < 1e-12 && std::abs(b.y() - 0.5) < 1e-12) {
      pairs.emplace_back(grid.E()(e, 0), grid.E()(e, 1));
      expected.push_back(e);
    }
  }
  ASSERT_EQ(expected.size(), 6u);
  pairs.emplace_back(0, grid.num_vertices() - 1);  // opposite corners: not an edge
  std::vector<int> identity(static_cast<std::size_t>(grid.num_vertices()));
  std::iota(identity.begin(), identity.end(), 0);
  RefusedFeatureEdge refused;
  FeatureOptions options;
  options.given = feature_segments(grid, identity, pairs, refused);
  EXPECT_EQ(refused.why, RefusedFeatureEdge::Why::kNotAnEdge);
  EXPECT_EQ(refused.position, 6);
  EXPECT_EQ(options.given->size(), 6u);
  // Through an input numbering: a vertex the input lacks, and one the mesh dropped (in no face).
  std::vector<int> dropped = identity;
  dropped[3] = -1;
  feature_segments(grid, dropped, {{0, 1}, {3, 4}}, refused);
  EXPECT_EQ(refused.why, RefusedFeatureEdge::Why::kVertexInNoFace);
  EXPECT_EQ(refused.position, 1);
  EXPECT_EQ(refused.vertex, 3);
  feature_segments(grid, identity, {{0, grid.num_vertices()}}, refused);
  EXPECT_EQ(refused.why, RefusedFeatureEdge::Why::kNoSuchVertex);
  EXPECT_EQ(refused.vertex, grid.num_vertices());
  EXPECT_EQ(feature_segments(grid, identity, {{1, 0}}, refused).size(), 1u);  // either order
  EXPECT_EQ(refused.why, RefusedFeatureEdge::Why::kNone);
  EXPECT_TRUE(has_sharp_features(options));
  const FeatureConstraints fc = feature_constraints(grid, options);
  EXPECT_EQ(fc.feature_edges, expected);
  EXPECT_TRUE(feature_constraints(grid).feature_edges.empty());  // not detected: the grid is flat
  for (int e : expected)
    for (int f : {grid.EF()(e, 0), grid.EF()(e, 1)}) {
      EXPECT_TRUE(fc.constrained[static_cast<std::size_t>(f)]) << f;
      const int source = fc.source_edge[static_cast<std::size_t>(f)];
      EXPECT_TRUE(source == e || grid.is_boundary_edge(source)) << f;  // a boundary beside it wins
    }
  const SplitMesh split = split_edges_at_midpoints(grid, {expected[1]});
  const Mesh refined = Mesh::from_triangles(split.V, split.F);
  EXPECT_EQ(feature_constraints(refined, options).feature_edges.size(), 7u);  // 5 whole and 2 halves
  FeatureOptions none;
  none.given.emplace();
  EXPECT_FALSE(has_sharp_features(none));
  EXPECT_TRUE(feature_constraints(grid, none).feature_edges.empty());
}

class FeatureMeshes : public ::testing::TestWithParam<std::string> {};

// Every constrained face's cross contains its curve direction exactly (up to rounding of one complex
// multiplication), it is trusted, and smoothing did not move it.
TEST_P(FeatureMeshes, ConstrainedCrossesContainCurveDirection) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  const FeatureConstraints fc = feature_constraints(mesh);
  const FrameFieldResult r = compute_frame_field_detailed(mesh);
  ASSERT_EQ(r.constrained, fc.constrained);
  int constrained = 0;
  for (int t = 0; t < mesh.num_faces(); ++t) {
    if (!fc.constrained[static_cast<std::size_t>(t)]) continue;
    ++constrained;
    const int e = fc.source_edge[static_cast<std::size_t>(t)];
    const Eigen::Vector3d d = (mesh.V().row(mesh.E()(e, 1)) - mesh.V().row(mesh.E()(e, 0))).normalized();
    const Eigen::Vector3d u = mesh.to_world(t, r.field.X[t]);
    // u ∥ d or u ⟂ d within the face plane: |u × d| · |u · d| = 0 and |u| = 1.
    EXPECT_LT(u.cross(d).norm() * std::abs(u.dot(d)), 1e-12) << "face " << t;
    EXPECT_NEAR(u.norm(), 1.0, 1e-12);
    EXPECT_TRUE(r.trusted[static_cast<std::size_t>(t)]);
    EXPECT_EQ(r.field.X[t], fc.direction[t]);  // smoothing kept α_t = 0 exactly
  }
  EXPECT_GT(constrained, 50);
}

INSTANTIATE_TEST_SUITE_P(Meshes, FeatureMeshes, ::testing::Values("fandisk", "mech_holes_shark", "camelhead_boundary"),
                         [](const auto& info) { return info.param; });

// Which faces are constrained: with min_curve_edges = 1, every face with a boundary edge or with an edge whose
// normals turn by more than the threshold, and nothing else. Disabling both removes all constraints.
TEST(Features, ThresholdAndBoundaryDetection) {
  for (const char* name : {"fandisk", "camelhead_boundary"}) {
    const Mesh mesh = testing::load_test_mesh(name);
    const Eigen::VectorXd beta = signed_dihedral_angles(mesh);
    FeatureOptions all;
    all.min_curve_edges = 1;
    const FeatureConstraints fc = feature_constraints(mesh, all);
    for (int t = 0; t < mesh.num_faces(); ++t) {
      bool expect = false;
      for (int k = 0; k < 3; ++k) {
        const int e = mesh.FE()(t, k);
        expect |= mesh.is_boundary_edge(e) || std::abs(beta[e]) > 35.0 * std::numbers::pi / 180;
      }
      ASSERT_EQ(fc.constrained[static_cast<std::size_t>(t)] != 0, expect) << name << " face " << t;
    }
    FeatureOptions off;
    off.boundaries = false;
    off.sharp_angle_degrees = 0;
    const FeatureConstraints none = feature_constraints(mesh, off);
    EXPECT_EQ(std::count(none.constrained.begin(), none.constrained.end(), 1), 0);
    EXPECT_TRUE(none.feature_edges.empty());
  }
}

// The curve filter keeps the creases of a CAD part (long chains) and drops isolated sharp edges of a coarse
// organic mesh; every kept edge has a continuing sharp neighbour.
TEST(Features, CurveFilter) {
  FeatureOptions all;
  all.min_curve_edges = 1;
  const Mesh fandisk = testing::load_test_mesh("fandisk");
  const auto f_all = feature_constraints(fandisk, all).feature_edges,
             f_kept = feature_constraints(fandisk).feature_edges;
  EXPECT_GT(f_kept.size(), 0.9 * f_all.size());  // min_curve_edges = 8 keeps 93 % on fandisk
  const Mesh bunny = testing::load_test_mesh("bunny_3k");
  const auto b_all = feature_constraints(bunny, all).feature_edges, b_kept = feature_constraints(bunny).feature_edges;
  EXPECT_LT(b_kept.size(), 0.6 * b_all.size());
  std::vector<int> count(static_cast<std::size_t>(bunny.num_vertices()), 0);
  for (int e : b_kept)
    for (int j = 0; j < 2; ++j) ++count[static_cast<std::size_t>(bunny.E()(e, j))];
  for (int e : b_kept)
    EXPECT_GE(count[static_cast<std::size_t>(bunny.E()(e, 0))] + count[static_cast<std::size_t>(bunny.E()(e, 1))], 3);
}

// Short crisp creases (FeatureOptions::crisp_crease_degrees): a gear's outline and tooth corners are chains of at most
// 3 sharp edges between 90° corners, every one between flat sides: all are followed, none without the rule. With
// arcs bending 7.5° an edge (6 teeth) the tooth tops are not crisp and the flanks alone make networks of 4 edges:
// none is followed until the limit is raised above 7.5°; nor what is shorter than crisp_min_length.
TEST(Features, CrispShortCreasesBetweenCornersAreFollowed) {
  FeatureOptions all;
  all.min_curve_edges = 1;
  const Mesh gear = testing::make_gear(12);
  const std::vector<int> sharp = feature_constraints(gear, all).feature_edges;
  EXPECT_EQ(sharp.size(), 2u * 96 + 24 * 2);
  EXPECT_EQ(feature_constraints(gear).feature_edges, sharp);
  FeatureOptions chains_only;
  chains_only.crisp_crease_degrees = 0;
  EXPECT_TRUE(feature_constraints(gear, chains_only).feature_edges.empty());
  const Mesh coarse = testing::make_gear(6);
  EXPECT_TRUE(feature_constraints(coarse).feature_edges.empty());
  FeatureOptions wider;
  wider.crisp_crease_degrees = 8;
  EXPECT_EQ(feature_constraints(coarse, wider).feature_edges, feature_constraints(coarse, all).feature_edges);
  // Chains shorter than crisp_min_length are not crisp creases: from 0.16 the roots (3 edges at radius 0.8, 0.157
  // long: 72 edges), from 0.2 the tooth tops too (0.196 long), and with them the rest, whose networks are then 4
  // edges (a flank's two outline edges and two corner edges).
  FeatureOptions longer;
  longer.crisp_min_length = 0.15;
  EXPECT_EQ(feature_constraints(gear, longer).feature_edges, sharp);
  longer.crisp_min_length = 0.16;
  EXPECT_EQ(feature_constraints(gear, longer).feature_edges.size(), sharp.size() - 72);
  longer.crisp_min_length = 0.2;
  EXPECT_TRUE(feature_constraints(gear, longer).feature_edges.empty());
}

// On real meshes, recomputed from the definition: every followed edge off the long chains is crisp (each edge of its
// faces that is not sharp bends by less than 5°), each of its ends meets another followed edge, and at least 8 such
// edges are joined to it.
TEST(Features, CrispCreasesOffTheChainsAreCrispAndBetweenCorners) {
  const double limit = 5.0 * std::numbers::pi / 180, sharp_angle = 35.0 * std::numbers::pi / 180;
  for (const char* name : {"fandisk", "bunny_3k", "couplingdown_genus9"}) {
    const Mesh mesh = testing::load_test_mesh(name);
    const Eigen::VectorXd beta = signed_dihedral_angles(mesh);
    FeatureOptions chains_only;
    chains_only.crisp_crease_degrees = 0;
    const std::vector<int> chains = feature_constraints(mesh, chains_only).feature_edges;
    const std::vector<int> kept = feature_constraints(mesh).feature_edges;
    std::vector<int> degree(static_cast<std::size_t>(mesh.num_vertices()), 0);
    for (int e : kept)
      for (int j = 0; j < 2; ++j) ++degree[static_cast<std::size_t>(mesh.E()(e, j))];
    std::vector<int> added;
    for (int e : kept) {
      if (std::binary_search(chains.begin(), chains.end(), e)) continue;
      added.push_back(e);
      for (int j = 0; j < 2; ++j) {
        EXPECT_GE(degree[static_cast<std::size_t>(mesh.E()(e, j))], 2) << name << " edge " << e;
        for (int k = 0; k < 3; ++k) {
          const int g = mesh.FE()(mesh.EF()(e, j), k);
          EXPECT_TRUE(std::abs(beta[g]) > sharp_angle || std::abs(beta[g]) < limit) << name << " edge " << e;
        }
      }
    }
    EXPECT_TRUE(std::includes(kept.begin(), kept.end(), chains.begin(), chains.end())) << name;
    detail::UnionFind joined(mesh.num_vertices());
    for (int e : added) joined.unite(mesh.E()(e, 0), mesh.E()(e, 1));
    std::vector<int> joined_edges(static_cast<std::size_t>(mesh.num_vertices()), 0);
    for (int e : added) ++joined_edges[static_cast<std::size_t>(joined.find(mesh.E()(e, 0)))];
    for (int e : added) EXPECT_GE(joined_edges[static_cast<std::size_t>(joined.find(mesh.E()(e, 0)))], 8) << name;
    if (std::string(name) == "fandisk") {
      EXPECT_EQ(added.size(), 20u);  // of the 54 sharp edges off its long chains
    }
  }
}

}  // namespace
}  // namespace quadcover
