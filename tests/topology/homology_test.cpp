// Homology generators from the cut graph, their dual cycles, Σ_k (1.13) and periods (Def. 1.14), thesis 1.2.5-1.2.6.
#include "topology/homology.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "calculus/div_curl.h"
#include "calculus/gradient.h"
#include "support/test_meshes.h"
#include "topology/base_sets.h"
#include "topology/harmonic_basis.h"

namespace quadcover {
namespace {

using testing::BaseSetCase;

class HomologyOnMeshes : public ::testing::TestWithParam<BaseSetCase> {
 protected:
  void SetUp() override {
    mesh_ = testing::load_test_mesh(GetParam().mesh);
    const auto base = testing::random_interior_vertices(mesh_, GetParam().num_base, GetParam().seed);
    graph_ = cut_graph(mesh_, base);
    basis_ = homology_basis(mesh_, graph_);
  }
  Mesh mesh_;
  CutGraph graph_;
  HomologyBasis basis_;
};

// dim H = 2g on closed surfaces, 2g + b - 1 with b > 0 boundary loops (thesis 1.2.5, extended to boundaries).
TEST_P(HomologyOnMeshes, NumberOfGeneratorsIsDimensionOfHarmonicSpace) {
  const ComponentInfo& c = mesh_.components()[0];
  EXPECT_EQ(basis_.size(), 2 * c.genus + (c.boundary_loops > 0 ? c.boundary_loops - 1 : 0));
  EXPECT_EQ(basis_.dual_cycles.size(), basis_.generators.size());
  EXPECT_EQ(graph_.num_loops, basis_.size());
}

// Generators are edge walks on the cut graph: closed loops away from the boundary, or boundary-to-boundary paths.
TEST_P(HomologyOnMeshes, GeneratorsAreWalksOnTheCutGraph) {
  for (const HomologyGenerator& g : basis_.generators) {
    ASSERT_EQ(g.vertices.size(), g.edges.size() + 1);
    ASSERT_GE(g.edges.size(), 1u);
    for (std::size_t i = 0; i < g.edges.size(); ++i) {
      const int e = g.edges[i], a = mesh_.E()(e, 0), b = mesh_.E()(e, 1);
      EXPECT_TRUE((a == g.vertices[i] && b == g.vertices[i + 1]) || (b == g.vertices[i] && a == g.vertices[i + 1]));
      EXPECT_EQ(graph_.cut[e], 1);
      if (i > 0) {
        EXPECT_NE(g.edges[i], g.edges[i - 1]) << "backtracking left in the walk";
      }
    }
    for (std::size_t i = 1; i + 1 < g.vertices.size(); ++i) EXPECT_FALSE(mesh_.is_boundary_vertex(g.vertices[i]));
    if (g.closed) {
      EXPECT_EQ(g.vertices.front(), g.vertices.back());
      EXPECT_FALSE(mesh_.is_boundary_vertex(g.vertices.front()));
      EXPECT_NE(g.edges.front(), g.edges.back());
    } else {
      EXPECT_TRUE(mesh_.is_boundary_vertex(g.vertices.front()));
      EXPECT_TRUE(mesh_.is_boundary_vertex(g.vertices.back()));
    }
  }
}

// The algebraic intersection number of γ_j* with γ_k, counted edge by edge with the sides of γ_k, is δ_jk.
TEST_P(HomologyOnMeshes, DualCyclesCrossOnlyTheirOwnGeneratorOnce) {
  const int n = basis_.size();
  for (int j = 0; j < n; ++j) {
    const DualCycle& d = basis_.dual_cycles[j];
    const std::size_t m = d.faces.size();
    ASSERT_EQ(d.edges.size(), m);
    for (std::size_t i = 0; i < m; ++i) {  // a closed walk in the dual graph
      const int e = d.edges[i], a = d.faces[i], b = d.faces[(i + 1) % m];
      EXPECT_TRUE((mesh_.EF()(e, 0) == a && mesh_.EF()(e, 1) == b) || (mesh_.EF()(e, 1) == a && mesh_.EF()(e, 0) == b));
    }
    for (int k = 0; k < n; ++k) {
      const HomologyGenerator& g = basis_.generators[k];
      int intersection = 0;
      for (std::size_t i = 0; i < m; ++i)
        for (std::size_t t = 0; t < g.edges.size(); ++t) {
          const int e = g.edges[t];
          if (e != d.edges[i]) continue;
          const int left = mesh_.EF()(e, g.vertices[t] == mesh_.E()(e, 0) ? 0 : 1);
          intersection += d.faces[i] == left ? 1 : -1;  // crossing from the left of γ_k to its right counts +1
        }
      EXPECT_EQ(intersection, j == k ? 1 : 0) << "dual cycle " << j << ", generator " << k;
    }
  }
}

// Σ_k is curl* free on interior edges (thesis 1.2.6) and b_j(Σ_k) = δ_jk.
TEST_P(HomologyOnMeshes, SigmaFieldsAreCurlFreeWithUnitPeriods) {
  const Eigen::SparseMatrix<Complex> sigma = sigma_fields(mesh_, basis_);
  ASSERT_EQ(sigma.rows(), mesh_.num_faces());
  ASSERT_EQ(sigma.cols(), basis_.size());
  for (int k = 0; k < basis_.size(); ++k) {
    const VectorField S = sigma.col(k);
    const Eigen::VectorXd c = curl_star(mesh_, S);
    double scale = 0, worst = 0;
    for (int e = 0; e < mesh_.num_edges(); ++e) {
      if (mesh_.is_boundary_edge(e)) continue;
      scale = std::max(scale, std::abs(S[mesh_.EF()(e, 0)]) * mesh_.edge_lengths()[e]);
      worst = std::max(worst, std::abs(c[e]));
    }
    EXPECT_GT(scale, 0);
    EXPECT_LE(worst, 1e-9 * scale) << "generator " << k;
    const Eigen::VectorXd b = periods(basis_, S);
    for (int j = 0; j < basis_.size(); ++j) EXPECT_NEAR(b[j], j == k ? 1.0 : 0.0, 1e-9) << j << "," << k;
  }
}

// Reversing a walk swaps its banks: Σ(γ) + Σ(γ reversed) = ∇w, w(p) = number of visits of γ at p; and
// walk_sigma_field agrees with the columns of sigma_fields.
TEST_P(HomologyOnMeshes, ReversedWalkComplementsSigma) {
  const Eigen::SparseMatrix<Complex> sigma = sigma_fields(mesh_, basis_);
  for (int k = 0; k < basis_.size(); ++k) {
    const HomologyGenerator& g = basis_.generators[k];
    const VectorField forward = walk_sigma_field(mesh_, g.vertices, g.closed);
    const VectorField column = sigma.col(k);
    EXPECT_LE((forward - column).cwiseAbs().maxCoeff(), 1e-12 * column.cwiseAbs().maxCoeff());
    const std::vector<int> reversed(g.vertices.rbegin(), g.vertices.rend());
    const VectorField backward = walk_sigma_field(mesh_, reversed, g.closed);
    Eigen::VectorXd visits = Eigen::VectorXd::Zero(mesh_.num_vertices());
    for (std::size_t i = 0; i < g.vertices.size() - (g.closed ? 1 : 0); ++i) visits[g.vertices[i]] += 1;
    const VectorField expected = gradient(mesh_, visits);
    EXPECT_LE((forward + backward - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
  }
}

// Corollary 1.15: periods of gradients vanish.
TEST_P(HomologyOnMeshes, GradientsHaveZeroPeriods) {
  std::mt19937 rng(GetParam().seed);
  std::uniform_real_distribution<double> unif(-1, 1);
  Eigen::VectorXd u(mesh_.num_vertices());
  for (int v = 0; v < u.size(); ++v) u[v] = unif(rng) / mesh_.mean_edge_length();
  const Eigen::VectorXd b = periods(basis_, gradient(mesh_, u));
  for (int j = 0; j < b.size(); ++j) EXPECT_NEAR(b[j], 0, 1e-9 * u.cwiseAbs().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(Meshes, HomologyOnMeshes,
                         ::testing::Values(BaseSetCase{"torus_5k", 0, 1}, BaseSetCase{"torus_5k", 5, 2},
                                           BaseSetCase{"eight_genus2", 0, 3}, BaseSetCase{"eight_genus2", 8, 4},
                                           BaseSetCase{"3holes_genus3", 3, 5}, BaseSetCase{"fertility_genus4", 0, 6},
                                           BaseSetCase{"couplingdown_genus9", 0, 7},
                                           BaseSetCase{"couplingdown_genus9", 6, 8}, BaseSetCase{"bunny_3k", 4, 9},
                                           BaseSetCase{"lilium_disk", 3, 10}, BaseSetCase{"mech_holes_shark", 0, 11},
                                           BaseSetCase{"mech_holes_shark", 5, 12},
                                           BaseSetCase{"bunny_20k_holes", 0, 13},
                                           BaseSetCase{"bunny_20k_holes", 4, 14}),
                         testing::base_set_case_name);

// A cylinder has one relative generator (a path from the bottom to the top circle) whose dual cycle runs around.
TEST(Homology, CylinderHasOneBoundaryToBoundaryGenerator) {
  const Mesh cylinder = testing::make_cylinder(24, 6);
  const HomologyBasis basis = homology_basis(cylinder, cut_graph(cylinder));
  ASSERT_EQ(basis.size(), 1);
  EXPECT_FALSE(basis.generators[0].closed);
  // The dual cycle winds once around the axis: its face centroids' angles turn by ±2π.
  double turn = 0;
  const auto& faces = basis.dual_cycles[0].faces;
  auto angle = [&](int f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += cylinder.V().row(cylinder.F()(f, k)).transpose();
    return std::atan2(c.y(), c.x());
  };
  for (std::size_t i = 0; i < faces.size(); ++i) {
    double d = angle(faces[(i + 1) % faces.size()]) - angle(faces[i]);
    d = std::remainder(d, 2 * std::numbers::pi);
    turn += d;
  }
  EXPECT_NEAR(std::abs(turn), 2 * std::numbers::pi, 1e-9);
}

// Two components (a torus and a cylinder): generators and dual cycles stay within their component.
TEST(Homology, ComponentsAreIndependent) {
  const Mesh both = testing::make_torus_and_cylinder();
  const HomologyBasis basis = homology_basis(both, cut_graph(both));
  ASSERT_EQ(basis.size(), 3);
  const Eigen::SparseMatrix<Complex> sigma = sigma_fields(both, basis);
  for (int k = 0; k < 3; ++k) {
    const int comp = both.vertex_component()[basis.generators[k].vertices[0]];
    for (const int f : basis.dual_cycles[k].faces) EXPECT_EQ(both.face_component()[f], comp);
    const Eigen::VectorXd b = periods(basis, sigma.col(k));
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(b[j], j == k ? 1.0 : 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace quadcover
