// Local evaluation of E_D (beyond thesis 6.2.1): the optimizer's view of the smoothing matrix (5.4) reproduces the
// FrameSmoother's re-smoothing, the local estimate equals the exact evaluation when the patch is the whole mesh,
// stays within a stated tolerance of it with the default patch, and batches do not depend on the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "field/compute_frame_field.h"
#include "optimize/curl_energy.h"
#include "optimize/curl_estimator.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

struct FieldCase {
  Mesh mesh;
  FrameFieldResult field;
  FrameSmoother smoother;
  explicit FieldCase(const char* name)
      : mesh(testing::load_test_mesh(name)),
        field(compute_frame_field_detailed(mesh)),
        smoother(mesh, field.field, field.stability, field.trusted, field.constrained, FieldOptions{}.lambda) {}
};

// Random single-edge changes and short paths (consecutive edges of a vertex fan, as branch point moves).
std::vector<std::vector<MatchingChange>> random_changes(const Mesh& mesh, int count, unsigned seed) {
  const auto edges = testing::interior_edges(mesh);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, edges.size() - 1);
  std::vector<std::vector<MatchingChange>> out;
  for (int i = 0; i < count; ++i) {
    std::vector<MatchingChange> c;
    if (i % 4 == 3) {
      const int v = mesh.E()(edges[pick(rng)], 0);
      for (const auto& fc : mesh.fan(v)) {
        const int e = mesh.FE()(fc.face, (fc.corner + 1) % 3);
        if (!mesh.is_boundary_edge(e) && c.size() < 3) c.push_back({e, i % 8 == 3 ? 1 : -1});
      }
    } else {
      c.push_back({edges[pick(rng)], rng() % 2 ? 1 : -1});
    }
    out.push_back(std::move(c));
  }
  return out;
}

// Δα of the smoother (two full solves) equals A⁻¹Δb of the optimizer's SmoothingSystem, globally and on a patch
// that covers the whole mesh.
TEST(SmoothingSystem, ReproducesTheSmoothersReSmoothing) {
  FieldCase s("bunny_3k");
  const SmoothingSystem A(s.mesh, s.smoother);
  const Eigen::VectorXd alpha0 = s.smoother.solve();
  const Eigen::VectorXd residual = A.multiply(alpha0);
  EXPECT_GT(residual.norm(), 0);
  LocalSmoothingWork work;
  for (int e : {17, 911, 2500}) {
    ASSERT_FALSE(s.mesh.is_boundary_edge(e));
    double theta = s.smoother.curvature()[e];
    FaceEntry fe[2];
    const int n = A.rhs_change(e, 1, theta, fe);
    ASSERT_GT(n, 0);
    s.smoother.change_matching(e, 1);
    EXPECT_NEAR(s.smoother.curvature()[e], theta, 1e-15);
    const Eigen::VectorXd dalpha = s.smoother.solve() - alpha0;
    s.smoother.change_matching(e, -1);
    Eigen::VectorXd db = Eigen::VectorXd::Zero(s.mesh.num_faces());
    for (int i = 0; i < n; ++i) db[fe[i].face] += fe[i].value;
    EXPECT_LT((A.solve(db) - dalpha).norm(), 1e-9 * dalpha.norm());
    A.solve_local(std::span(fe, n), 1 << 20, 1e-13, work);
    Eigen::VectorXd local = Eigen::VectorXd::Zero(s.mesh.num_faces());
    for (std::size_t i = 0; i < work.faces.size(); ++i) local[work.faces[i]] = work.x[i];
    EXPECT_LT((local - dalpha).norm(), 1e-8 * dalpha.norm());
  }
}

// With the patch = the whole mesh the model is exact: estimate() equals evaluate() (full re-smoothing, full
// forward solve) up to round-off, for single edges and paths.
TEST(LocalEstimate, EqualsExactEvaluationWhenThePatchIsTheWholeMesh) {
  FieldCase s("eight_genus2");
  CurlEnergyOptions o;
  o.local_rings = 1 << 20;
  o.local_tolerance = 1e-14;
  CurlEnergy ed(s.mesh, s.smoother, o);
  CurlEstimator est_ed(ed);
  est_ed.prepare();
  EstimateWorkspace ws;
  for (const auto& c : random_changes(s.mesh, 12, 5)) {
    const double exact = ed.evaluate(c);
    const double est = est_ed.estimate(c, ws);
    EXPECT_NEAR(est, exact, 1e-9 * exact);
  }
}

// Default patch (6 rings + first-order far field). Stated tolerance, per change: |estimate - exact| <= 2% of E_D
// (measured worst 1.6% on bunny_3k, 0.17% on lilium_disk; a change whose exact ΔE_D is within that band may be
// estimated on the wrong side of E_D). The local re-smoothing is what makes it close: with rings = 0 (first order
// only) the worst error is larger.
TEST(LocalEstimate, DefaultPatchIsWithinTheStatedTolerance) {
  for (const char* name : {"bunny_3k", "lilium_disk"}) {
    FieldCase s(name);
    CurlEnergyOptions first_order;
    first_order.local_rings = 0;
    CurlEnergy ed(s.mesh, s.smoother), ed0(s.mesh, s.smoother, first_order);
    CurlEstimator est_ed(ed), est_ed0(ed0);
    est_ed.prepare(), est_ed0.prepare();
    const double e0 = ed.energy();
    EstimateWorkspace ws;
    double worst = 0, worst0 = 0;
    for (const auto& c : random_changes(s.mesh, 40, 9)) {
      const double exact = ed.evaluate(c);
      const double est = est_ed.estimate(c, ws);
      worst = std::max(worst, std::abs(est - exact) / e0);
      worst0 = std::max(worst0, std::abs(est_ed0.estimate(c, ws) - exact) / e0);
      EXPECT_LT(std::abs(est - exact), 0.02 * e0) << name << " change at edge " << c[0].edge;
    }
    EXPECT_LT(worst, worst0) << name;
  }
}

// estimate_batch is deterministic: 1 thread and 2 threads give bitwise identical values, equal to serial calls.
TEST(LocalEstimate, BatchDoesNotDependOnTheThreadCount) {
  FieldCase s("bunny_3k");
  CurlEnergy ed(s.mesh, s.smoother);
  CurlEstimator est_ed(ed);
  const auto cands = random_changes(s.mesh, 64, 21);
  std::vector<double> one(cands.size()), two(cands.size());
  est_ed.estimate_batch(cands, one, 1);
  est_ed.estimate_batch(cands, two, 2);
  EstimateWorkspace ws;
  for (std::size_t i = 0; i < cands.size(); ++i) {
    EXPECT_EQ(one[i], two[i]) << i;
    EXPECT_EQ(one[i], est_ed.estimate(cands[i], ws)) << i;
  }
  EXPECT_EQ(est_ed.timings().evaluations, 128);
}

// The estimator follows the energy's state: after a commit it must be prepared again, and a commit within
// estimate_refresh keeps the stale far field (the estimate still differs from a fresh estimator's only there).
TEST(LocalEstimate, EstimatesNeedAPrepareAfterEveryCommit) {
  FieldCase s("bunny_3k");
  CurlEnergy ed(s.mesh, s.smoother);
  CurlEstimator est_ed(ed);
  EstimateWorkspace ws;
  const auto cands = random_changes(s.mesh, 2, 33);
  EXPECT_THROW(est_ed.estimate(cands[0], ws), std::logic_error);
  est_ed.prepare();
  ed.evaluate(cands[0]);
  ed.commit();
  EXPECT_THROW(est_ed.estimate(cands[1], ws), std::logic_error);
  est_ed.prepare();  // stale far field (1 commit < estimate_refresh)
  CurlEstimator fresh(ed);
  fresh.prepare();
  const double stale = est_ed.estimate(cands[1], ws), current = fresh.estimate(cands[1], ws);
  EXPECT_NE(stale, current);
  EXPECT_NEAR(stale, current, 0.02 * ed.energy());
  ed.recompute_from_scratch();  // a rebuild needs a full prepare
  EXPECT_THROW(est_ed.estimate(cands[1], ws), std::logic_error);
}

}  // namespace
}  // namespace quadcover
