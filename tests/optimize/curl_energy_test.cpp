// E_D re-evaluation through Cholesky updates (6.2.1) on real frame fields: predictions of evaluate() equal E_D
// recomputed from scratch (fresh 𝔏̄*, fresh factorization) after sequences of single-edge and path changes.
#include "optimize/curl_energy.h"

#include <gtest/gtest.h>

#include <random>

#include "field/compute_frame_field.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

struct FieldSetup {
  Mesh mesh;
  FrameFieldResult field;
  FrameSmoother smoother;
  explicit FieldSetup(const char* name)
      : mesh(testing::load_test_mesh(name)),
        field(compute_frame_field_detailed(mesh)),
        smoother(mesh, field.field, field.stability, field.trusted, field.constrained, FieldOptions{}.lambda) {}
};

class CurlOnMeshes : public ::testing::TestWithParam<const char*> {};

TEST_P(CurlOnMeshes, UpdatedEnergyEqualsFreshRecomputation) {
  FieldSetup s(GetParam());
  CurlEnergy ed(s.mesh, s.smoother);
  const double e0 = ed.energy();
  ASSERT_GT(e0, 0);
  const auto edges = testing::interior_edges(s.mesh);
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::size_t> pick(0, edges.size() - 1);
  for (int it = 0; it < 60; ++it) {
    std::vector<MatchingChange> changes;
    if (it % 5 == 4) {  // a path: consecutive edges of one face fan (a branch point move over several edges)
      const int v = s.mesh.E()(edges[pick(rng)], 0);
      for (const auto& fc : s.mesh.fan(v)) {
        const int e = s.mesh.FE()(fc.face, (fc.corner + 1) % 3);
        if (!s.mesh.is_boundary_edge(e) && changes.size() < 3) changes.push_back(MatchingChange{e, 1});
      }
    } else {
      changes.push_back(MatchingChange{edges[pick(rng)], it % 2 ? 1 : -1});
    }
    const double predicted = ed.evaluate(changes);
    ASSERT_TRUE(std::isfinite(predicted)) << "update failed at step " << it;
    ed.commit();
    EXPECT_NEAR(ed.energy(), predicted, 1e-12 * predicted);
  }
  const double updated = ed.energy();
  const double fresh = ed.recompute_from_scratch();
  EXPECT_NEAR(updated, fresh, 1e-9 * fresh);
  EXPECT_NE(updated, e0);  // the changes did change E_D
}

// evaluate() without commit() changes nothing; committing and recomputing reproduces the prediction.
TEST_P(CurlOnMeshes, EvaluationWithoutCommitLeavesStateUntouched) {
  FieldSetup s(GetParam());
  CurlEnergy ed(s.mesh, s.smoother);
  const double e0 = ed.energy();
  const Eigen::VectorXi m0 = ed.matching();
  const auto edges = testing::interior_edges(s.mesh);
  const MatchingChange c{edges[edges.size() / 3], 1};
  const double predicted = ed.evaluate(std::span(&c, 1));
  EXPECT_EQ(ed.energy(), e0);
  EXPECT_EQ(ed.matching(), m0);
  EXPECT_EQ(s.smoother.matching(), m0);
  ed.commit();
  EXPECT_EQ(ed.matching()[c.edge], m0[c.edge] + 1);
  EXPECT_NEAR(ed.recompute_from_scratch(), predicted, 1e-9 * predicted);
}

// The ordering made ahead of the field (beside the field stage) is the one the factor of the field's E_D has: the
// pattern does not depend on the matching (bunny_3k's field has branch points, lilium_disk's boundary edges are
// pinned). eight_genus2's 951 edges are ordered by CXSparse's AMD instead, with the factor.
TEST(CurlEnergyOrdering, OrderingMadeAheadIsTheFactorsOrdering) {
  for (const char* name : {"bunny_3k", "lilium_disk", "eight_genus2"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = testing::load_test_mesh(name);
    const std::vector<int> ahead = order_curl_energy_ahead(mesh);
    FieldSetup s(name);
    ASSERT_NE(s.field.field.matching, Eigen::VectorXi::Zero(s.mesh.num_edges()));
    const CurlEnergy ed(s.mesh, s.smoother);
    ASSERT_EQ(ed.factor().perm().size(), static_cast<std::size_t>(mesh.num_edges()));
    if (mesh.num_edges() < 1000) {
      EXPECT_TRUE(ahead.empty());
    } else {
      EXPECT_EQ(ed.factor().perm(), ahead);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Fields, CurlOnMeshes, ::testing::Values("bunny_3k", "eight_genus2", "lilium_disk"));

}  // namespace
}  // namespace quadcover
