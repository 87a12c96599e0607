// The jump function of translations on the cut (thesis 1.13, 4.2.1) and the unit jump fields of the period matrix
// (6.3.2), made from the cut's fans walked once per translation vector (param/cut_fans.h): the transitions
// φ_t = i^{k_e} φ_s + c_e hold across every cut edge at both endpoints, the values agree across uncut edges and are
// 0 off the cut; reusing one scratch memory from path to path gives the fields of fresh calls.
#include "param/disk_functions.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "common/quarter_turn.h"
#include "field/compute_frame_field.h"
#include "param/period_matrix.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::load_test_mesh;

// Random translations on the path edges, completed to the whole cut.
Eigen::VectorXcd random_translations(const Mesh& mesh, const CoverCut& cc, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-3, 3);
  Eigen::VectorXcd c = Eigen::VectorXcd::Zero(mesh.num_edges());
  for (int j = 0; j < cc.num_paths(); ++j) c[cc.path_edge[j]] = Complex(U(rng), U(rng));
  complete_translations(mesh, cc, c);
  return c;
}

// Largest violation of the transitions across cut edges, of continuity across uncut edges, and of 0 off the cut.
double jump_violation(const Mesh& mesh, const CoverCut& cc, const Eigen::VectorXcd& c, const Eigen::MatrixX3cd& sigma) {
  double worst = 0;
  std::vector<char> on_cut(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (cc.graph.cut[e]) on_cut[mesh.E()(e, 0)] = on_cut[mesh.E()(e, 1)] = 1;
    if (mesh.is_boundary_edge(e)) continue;
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    for (int end = 0; end < 2; ++end) {
      const int v = mesh.E()(e, end);
      const Complex from = sigma(s, mesh.corner_of(s, v)), to = sigma(t, mesh.corner_of(t, v));
      const Complex expected = cc.graph.cut[e] ? ipow(cc.rotation[e]) * from + c[e] : from;
      worst = std::max(worst, std::abs(to - expected));
    }
  }
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (!on_cut[mesh.F()(f, k)]) worst = std::max(worst, std::abs(sigma(f, k)));
  return worst;
}

TEST(JumpFunction, MeetsTheTransitionsOnTheCutAndIsZeroOffIt) {
  for (const char* name : {"eight_genus2", "3holes_genus3", "lilium_disk"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = load_test_mesh(name);
    const CoverCut cc = build_cover_cut(mesh, compute_frame_field(mesh).matching);
    ASSERT_GT(cc.num_paths(), 0);
    const CutFans fans = cut_fans(mesh, cc);
    for (unsigned seed : {1u, 2u}) {
      const Eigen::VectorXcd c = random_translations(mesh, cc, seed);
      EXPECT_LT(jump_violation(mesh, cc, c, jump_function(mesh, cc, fans, c)), 1e-9);
    }
    // One path's translations: non-zero on part of the cut only, the other fans stay 0.
    Eigen::VectorXcd c = Eigen::VectorXcd::Zero(mesh.num_edges());
    c[cc.path_edge[0]] = Complex(0.5, -2);
    complete_translations(mesh, cc, fans, c);
    const Eigen::MatrixX3cd sigma = jump_function(mesh, cc, fans, c);
    EXPECT_LT(jump_violation(mesh, cc, c, sigma), 1e-9);
    EXPECT_GT(sigma.cwiseAbs().maxCoeff(), 0.1);
  }
}

TEST(UnitJumpField, ReusedScratchGivesTheFieldsOfFreshCalls) {
  for (const char* name : {"3holes_genus3", "lilium_disk"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = load_test_mesh(name);
    const CoverCut cc = build_cover_cut(mesh, compute_frame_field(mesh).matching);
    const CutFans fans = cut_fans(mesh, cc);
    std::vector<int> order(static_cast<std::size_t>(cc.num_paths()));
    for (int j = 0; j < cc.num_paths(); ++j) order[j] = j;
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    JumpScratch scratch;
    for (const int j : order) {
      const SparseJumpField reused = unit_jump_field(mesh, cc, fans, j, scratch);
      const SparseJumpField fresh = unit_jump_field(mesh, cc, j);
      ASSERT_EQ(reused.support, fresh.support) << "path " << j;
      ASSERT_FALSE(fresh.support.empty()) << "path " << j;
      EXPECT_EQ(reused.X, fresh.X) << "path " << j;
      EXPECT_EQ(reused.Y, fresh.Y) << "path " << j;
    }
    EXPECT_EQ(scratch.c.cwiseAbs().maxCoeff(), 0);
    EXPECT_EQ(scratch.sigma.cwiseAbs().maxCoeff(), 0);
  }
}

}  // namespace
}  // namespace quadcover
