// Termination and budgets of Algorithm 6.1 (thesis 6.2.2): relocation on a grid with hundreds of square holes
// (many boundary loops) converges with a bounded number of evaluations; the default budget grows with the mesh and
// is capped; the report says whether a run converged or what stopped it; the stale far-field correction of the
// screening (CurlEnergyOptions::estimate_refresh) refreshes ∇_α E_D and z only every few commits and leaves every
// accepted move exactly confirmed.
#include <gtest/gtest.h>

#include <algorithm>

#include "field/compute_frame_field.h"
#include "field/indices.h"
#include "optimize/curl_reduction.h"
#include "optimize/optimize_field.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// An n × n grid with the quads (i, j), i and j odd and < n - 2, removed: ((n - 2) / 2)² square holes.
Mesh grid_with_holes(int n) {
  const Mesh grid = testing::make_grid(n);
  std::vector<int> keep;
  for (int f = 0; f < grid.num_faces(); ++f) {
    const int quad = f / 2, i = quad % n, j = quad / n;
    if (!(i % 2 == 1 && j % 2 == 1 && i < n - 2 && j < n - 2)) keep.push_back(f);
  }
  Eigen::MatrixX3i F(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t k = 0; k < keep.size(); ++k) F.row(static_cast<Eigen::Index>(k)) = grid.F().row(keep[k]);
  return Mesh::from_triangles(grid.V(), F);
}

TEST(OptimizeBudget, RelocationOnManyHolesConvergesWithBoundedEvaluations) {
  const Mesh mesh = grid_with_holes(32);  // 15² = 225 holes
  const FrameFieldResult field = compute_frame_field_detailed(mesh);
  OptimizeOptions o;
  o.mode = OptimizeMode::Relocate;
  // A cap of 50 screened evaluations per interior edge (measured: 8 to 18): the run must converge below it.
  const long edges = static_cast<long>(testing::interior_edges(mesh).size());
  o.max_evaluations = 50 * edges;
  const OptimizeResult r = optimize_field(mesh, field, o);
  const auto j = to_json(r, o.mode);
  EXPECT_EQ(j["stopped_by"], "converged");
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_FALSE(r.reduction.stopped_early);
  // Every pass screens each interior edge at most once and all but the last accept a strict E_D decrease.
  EXPECT_GT(r.reduction.evaluations, 0);
  EXPECT_LT(r.reduction.evaluations, o.max_evaluations);
  EXPECT_LE(r.reduction.exact_evaluations, r.reduction.evaluations);
  // Relocation never creates branch points and never increases E_D.
  EXPECT_LE(r.reduction.final_branch_points, r.reduction.initial_branch_points);
  for (std::size_t i = 1; i < r.reduction.log.size(); ++i)
    EXPECT_LT(r.reduction.log[i].energy, r.reduction.log[i - 1].energy) << "entry " << i;
  EXPECT_EQ(r.reduction.final_branch_points, count_branch_points(mesh, matching_quarter_index(mesh, r.field.matching)));
}

TEST(OptimizeBudget, AutoBudgetGrowsWithTheMeshAndIsCapped) {
  const Mesh small = grid_with_holes(12), large = testing::load_test_mesh("bunny_20k_holes");
  // relocate: 3000 up to 33k faces (the budget of the e2e baselines), then 1e8 evaluated faces, at least 300;
  // full: grows with the interior edges.
  EXPECT_EQ(auto_evaluation_budget(small, OptimizeMode::Relocate), 3000);
  EXPECT_EQ(auto_evaluation_budget(large, OptimizeMode::Relocate), 3000);
  EXPECT_EQ(auto_evaluation_budget(testing::make_torus(250, 100), OptimizeMode::Relocate), 2000);  // 50k faces
  EXPECT_EQ(auto_evaluation_budget(testing::make_torus(400, 250), OptimizeMode::Relocate), 500);   // 200k
  EXPECT_EQ(auto_evaluation_budget(testing::make_torus(500, 400), OptimizeMode::Relocate), 300);   // 400k: the floor
  EXPECT_EQ(auto_evaluation_budget(small, OptimizeMode::Full), 3000);  // the floor
  EXPECT_GT(auto_evaluation_budget(large, OptimizeMode::Full), 3000);
  EXPECT_EQ(auto_evaluation_budget(large, OptimizeMode::Full),
            static_cast<long>(testing::interior_edges(large).size()) / 8);
  // The auto time limit: full only, growing with the faces.
  EXPECT_EQ(auto_time_limit(small, OptimizeMode::Relocate), 0.0);
  EXPECT_GT(auto_time_limit(large, OptimizeMode::Full), auto_time_limit(small, OptimizeMode::Full));
}

TEST(OptimizeBudget, ReportSaysWhetherTheRunConvergedOrStoppedOnTheBudget) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const FrameFieldResult field = compute_frame_field_detailed(mesh);
  OptimizeOptions o;
  o.mode = OptimizeMode::Relocate;
  o.max_evaluations = 60;
  OptimizeResult r = optimize_field(mesh, field, o);
  auto j = to_json(r, o.mode);
  EXPECT_EQ(j["stopped_by"], "evaluations");
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_EQ(j["max_evaluations"].get<long>(), 60);
  EXPECT_GE(j["evaluations"].get<long>(), 60);
  // The default (auto) budget is the one reported; relocation on bunny_3k converges within it.
  o.max_evaluations = kAutoBudget;
  r = optimize_field(mesh, field, o);
  j = to_json(r, o.mode);
  EXPECT_EQ(j["max_evaluations"].get<long>(), auto_evaluation_budget(mesh, OptimizeMode::Relocate));
  EXPECT_EQ(j["stopped_by"], "converged");
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_LT(j["evaluations"].get<long>(), j["max_evaluations"].get<long>());
  EXPECT_EQ(to_json(r, OptimizeMode::None)["stopped_by"], "converged");
}

TEST(OptimizeBudget, StaleFarFieldRefreshesEveryFewCommitsAndAcceptedMovesStayExact) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const FrameFieldResult field = compute_frame_field_detailed(mesh);
  CurlReductionOptions ro;
  ro.max_evaluations = 600;
  long prepares[2] = {0, 0}, accepted[2] = {0, 0};
  for (int refresh : {1, 8}) {
    FrameSmoother smoother(mesh, field.field, field.stability, field.trusted, field.constrained, FieldOptions{}.lambda);
    CurlEnergyOptions eo;
    eo.estimate_refresh = refresh;
    CurlEnergy energy(mesh, smoother, eo);
    const CurlReductionResult r = reduce_curl(mesh, energy, ro);
    const int k = refresh == 1 ? 0 : 1;
    prepares[k] = energy.timings().prepares, accepted[k] = r.accepted;
    ASSERT_GT(r.accepted, 8);
    for (std::size_t i = 1; i < r.log.size(); ++i) EXPECT_LT(r.log[i].energy, r.log[i - 1].energy) << "entry " << i;
    // The state is exact: a fresh factorization and full re-smoothing of the final matching give the same E_D.
    EXPECT_NEAR(energy.recompute_from_scratch(), r.final_energy, 1e-9 * r.final_energy);
  }
  // refresh 1: once per commit (plus the start); refresh 8: at most once per 8 commits (plus the start).
  EXPECT_GE(prepares[0], accepted[0]);
  EXPECT_LE(prepares[1], accepted[1] / 8 + 1);
}

}  // namespace
}  // namespace quadcover
