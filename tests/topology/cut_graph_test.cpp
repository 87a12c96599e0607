// Algorithm 1.16 with base sets and boundaries (thesis 1.3.1, [KNP10]) on real meshes of genus 0-9, with and
// without boundary, and with random base sets.
#include "topology/cut_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "common/errors.h"
#include "common/union_find.h"
#include "support/test_meshes.h"
#include "topology/base_sets.h"

namespace quadcover {
namespace {

using testing::BaseSetCase;
std::string case_name(const ::testing::TestParamInfo<BaseSetCase>& info) {
  return info.param.mesh + "_B" + std::to_string(info.param.num_base) + "_s" + std::to_string(info.param.seed);
}

class CutGraphOnMeshes : public ::testing::TestWithParam<BaseSetCase> {
 protected:
  void SetUp() override {
    mesh_ = testing::load_test_mesh(GetParam().mesh);
    base_ = testing::random_interior_vertices(mesh_, GetParam().num_base, GetParam().seed);
    graph_ = cut_graph(mesh_, base_);
  }
  Mesh mesh_;
  std::vector<int> base_;
  CutGraph graph_;
};

// Per component: rank H1 of M with B ∪ ∂M identified to a point = 2g + b + |B| - 1 (|B| >= 1 counting the root).
TEST_P(CutGraphOnMeshes, PathCountIsRankOfIdentifiedHomology) {
  ASSERT_EQ(mesh_.num_components(), 1);
  const ComponentInfo& c = mesh_.components()[0];
  const int interior_sources = static_cast<int>(graph_.sources.size()) - [&] {
    int nb = 0;
    for (int v = 0; v < mesh_.num_vertices(); ++v) nb += mesh_.is_boundary_vertex(v);
    return nb;
  }();
  EXPECT_EQ(interior_sources, c.boundary_loops > 0 || !base_.empty() ? static_cast<int>(base_.size()) : 1);
  EXPECT_EQ(static_cast<int>(graph_.paths.size()), 2 * c.genus + c.boundary_loops + interior_sources - 1);
}

// Each σ(e) is an edge path between two sources that meets no other source; the cut flags are their union.
TEST_P(CutGraphOnMeshes, PathsAreEdgePathsBetweenSources) {
  const std::set<int> sources(graph_.sources.begin(), graph_.sources.end());
  Eigen::VectorXi expected_cut = Eigen::VectorXi::Zero(mesh_.num_edges());
  for (const CutPath& p : graph_.paths) {
    ASSERT_EQ(p.vertices.size(), p.edges.size() + 1);
    EXPECT_TRUE(sources.count(p.vertices.front()));
    EXPECT_TRUE(sources.count(p.vertices.back()));
    for (std::size_t i = 1; i + 1 < p.vertices.size(); ++i) EXPECT_FALSE(sources.count(p.vertices[i]));
    double length = 0;
    for (std::size_t i = 0; i < p.edges.size(); ++i) {
      const int e = p.edges[i];
      const int a = mesh_.E()(e, 0), b = mesh_.E()(e, 1);
      EXPECT_TRUE((a == p.vertices[i] && b == p.vertices[i + 1]) || (b == p.vertices[i] && a == p.vertices[i + 1]));
      EXPECT_FALSE(mesh_.is_boundary_edge(e));
      length += mesh_.edge_lengths()[e];
      expected_cut[e] = 1;
    }
    EXPECT_NEAR(p.length, length, 1e-12 * (1 + length));
    EXPECT_NE(graph_.parent_edge[mesh_.E()(p.leftover_edge, 0)], p.leftover_edge);
    EXPECT_NE(graph_.parent_edge[mesh_.E()(p.leftover_edge, 1)], p.leftover_edge);
    EXPECT_EQ(graph_.cotree[p.leftover_edge], 0);
  }
  EXPECT_EQ(graph_.cut, expected_cut);
}

// Step 1: T is a shortest-path forest: distances satisfy the triangle inequality on every edge and are tight on
// tree edges; sources have distance 0.
TEST_P(CutGraphOnMeshes, ForestIsShortestPathForest) {
  const Eigen::VectorXd& d = graph_.distance;
  for (const int s : graph_.sources) EXPECT_EQ(d[s], 0.0);
  for (int e = 0; e < mesh_.num_edges(); ++e) {
    const int a = mesh_.E()(e, 0), b = mesh_.E()(e, 1);
    EXPECT_LE(std::abs(d[a] - d[b]), mesh_.edge_lengths()[e] * (1 + 1e-12));
  }
  for (int v = 0; v < mesh_.num_vertices(); ++v) {
    const int e = graph_.parent_edge[v];
    if (e < 0) {
      EXPECT_EQ(d[v], 0.0);
      continue;
    }
    const int u = mesh_.E()(e, 0) + mesh_.E()(e, 1) - v;
    EXPECT_NEAR(d[v], d[u] + mesh_.edge_lengths()[e], 1e-12 * (1 + d[v]));
    EXPECT_EQ(graph_.root[v], graph_.root[u]);
  }
}

// Step 2: T* is a spanning tree of the dual graph avoiding T: f - 1 dual edges connecting all faces.
TEST_P(CutGraphOnMeshes, CotreeSpansTheDualGraph) {
  detail::UnionFind faces(mesh_.num_faces());
  int count = 0;
  for (int e = 0; e < mesh_.num_edges(); ++e) {
    if (!graph_.cotree[e]) continue;
    ++count;
    EXPECT_FALSE(mesh_.is_boundary_edge(e));
    EXPECT_FALSE(graph_.cut[e]);
    EXPECT_TRUE(faces.unite(mesh_.EF()(e, 0), mesh_.EF()(e, 1))) << "cycle in T* at edge " << e;
  }
  EXPECT_EQ(count, mesh_.num_faces() - 1);
}

// The cut reaches every base vertex and every boundary loop (else the identified surface would not be a disk).
TEST_P(CutGraphOnMeshes, CutTouchesEveryBaseVertexAndBoundaryLoop) {
  if (graph_.paths.empty()) {  // only a sphere with |B| <= 1 or a disk with B = {} needs no cut
    EXPECT_EQ(mesh_.genus(), 0);
    EXPECT_LE(base_.size() + mesh_.num_boundary_loops(), 1u);
    return;
  }
  std::vector<char> on_cut(static_cast<std::size_t>(mesh_.num_vertices()), 0);
  for (const CutPath& p : graph_.paths)
    for (const int v : p.vertices) on_cut[v] = 1;
  for (const int b : base_) EXPECT_TRUE(on_cut[b]) << "base vertex " << b;
  for (const auto& loop : mesh_.boundary_loops()) {
    bool touched = false;
    for (const int v : loop) touched = touched || on_cut[v];
    EXPECT_TRUE(touched);
  }
}

TEST_P(CutGraphOnMeshes, IsDeterministic) {
  const CutGraph again = cut_graph(mesh_, base_);
  EXPECT_EQ(again.cut, graph_.cut);
  ASSERT_EQ(again.paths.size(), graph_.paths.size());
  for (std::size_t i = 0; i < again.paths.size(); ++i) EXPECT_EQ(again.paths[i].vertices, graph_.paths[i].vertices);
}

INSTANTIATE_TEST_SUITE_P(Meshes, CutGraphOnMeshes,
                         ::testing::Values(BaseSetCase{"torus_5k", 0, 1}, BaseSetCase{"torus_5k", 4, 2},
                                           BaseSetCase{"eight_genus2", 0, 1}, BaseSetCase{"eight_genus2", 7, 3},
                                           BaseSetCase{"3holes_genus3", 0, 1}, BaseSetCase{"fertility_genus4", 0, 1},
                                           BaseSetCase{"couplingdown_genus9", 0, 1},
                                           BaseSetCase{"couplingdown_genus9", 5, 4}, BaseSetCase{"bunny_3k", 0, 1},
                                           BaseSetCase{"bunny_3k", 5, 5}, BaseSetCase{"spot", 2, 6},
                                           BaseSetCase{"cow", 12, 7}, BaseSetCase{"lilium_disk", 0, 1},
                                           BaseSetCase{"lilium_disk", 3, 8}, BaseSetCase{"camelhead_boundary", 4, 9},
                                           BaseSetCase{"mech_holes_shark", 0, 1},
                                           BaseSetCase{"bunny_20k_holes", 6, 10}),
                         case_name);

// With one base vertex on a closed surface the output is a system of 2g loops (thesis 1.3): on a torus of revolution
// the shortest loop is the meridian through the base vertex, n_minor chords of the tube circle.
TEST(CutGraph, TorusSystemOfLoopsContainsTheMeridian) {
  const int n_major = 40, n_minor = 12;
  const double R = 2.0, r = 0.7;
  const Mesh torus = testing::make_torus(n_major, n_minor, R, r);
  const std::vector<int> base{0};
  const CutGraph g = cut_graph(torus, base);
  ASSERT_EQ(g.paths.size(), 2u);
  double shortest = 1e300;
  for (const CutPath& p : g.paths) {
    EXPECT_EQ(p.vertices.front(), 0);
    EXPECT_EQ(p.vertices.back(), 0);
    shortest = std::min(shortest, p.length);
  }
  EXPECT_NEAR(shortest, n_minor * 2 * r * std::sin(std::numbers::pi / n_minor), 1e-12);
}

// A sphere with at most one base vertex is simply connected: no path; a disk without base vertices likewise.
TEST(CutGraph, SimplyConnectedCasesNeedNoCut) {
  EXPECT_TRUE(cut_graph(testing::make_ellipsoid(2)).paths.empty());
  EXPECT_TRUE(cut_graph(testing::make_grid(6)).paths.empty());
  // A cylinder (b = 2) needs one path joining its two boundary circles.
  const Mesh cylinder = testing::make_cylinder(16, 5);
  const CutGraph g = cut_graph(cylinder);
  ASSERT_EQ(g.paths.size(), 1u);
  const double z0 = cylinder.V()(g.paths[0].vertices.front(), 2), z1 = cylinder.V()(g.paths[0].vertices.back(), 2);
  EXPECT_NEAR(std::abs(z1 - z0), 2.0, 1e-12);
}

TEST(CutGraph, CustomWeightsChangeTheTree) {
  const Mesh torus = testing::make_torus(20, 10);
  CutGraphOptions unit;
  unit.edge_weights = Eigen::VectorXd::Ones(torus.num_edges());
  const CutGraph g = cut_graph(torus, std::vector<int>{0}, unit);
  for (int v = 0; v < torus.num_vertices(); ++v) EXPECT_EQ(g.distance[v], std::round(g.distance[v]));
  EXPECT_EQ(g.paths.size(), 2u);
}

TEST(CutGraph, RejectsInvalidInput) {
  const Mesh torus = testing::make_torus(8, 6);
  EXPECT_THROW(cut_graph(torus, std::vector<int>{torus.num_vertices()}), InputError);
  EXPECT_THROW(cut_graph(torus, std::vector<int>{-1}), InputError);
  CutGraphOptions bad;
  bad.edge_weights = Eigen::VectorXd::Ones(torus.num_edges() - 1);
  EXPECT_THROW(cut_graph(torus, {}, bad), InputError);
  bad.edge_weights = Eigen::VectorXd::Ones(torus.num_edges());
  (*bad.edge_weights)[3] = 0;
  EXPECT_THROW(cut_graph(torus, {}, bad), InputError);
}

}  // namespace
}  // namespace quadcover
