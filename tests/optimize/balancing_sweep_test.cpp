// Figure 6.5 sweep (thesis 6.4): along balancing, cancelling pairs raises E_D; rows are sorted by branch point
// count, E_H is a parameterization's continuity distortion (>= 0) and the total is their sum.
#include "optimize/balancing_sweep.h"

#include <gtest/gtest.h>

#include "field/compute_frame_field.h"
#include "field/indices.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

TEST(BalancingSweep, CurlDistortionRisesAsPairsAreCancelled) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const FrameFieldResult field = compute_frame_field_detailed(mesh);
  BalancingSweepOptions o;
  o.optimize.max_evaluations = 0;  // converge every step
  o.max_rows = 6;
  o.allow_creation = false;  // from the field's own branch points (fast); the benchmark sweeps with creation
  const std::vector<BalancingSweepRow> rows = balancing_sweep(mesh, field, o);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_GE(rows[i].energy_harmonic, 0);
    EXPECT_GT(rows[i].energy_curl, 0);
    EXPECT_DOUBLE_EQ(rows[i].total, rows[i].energy_curl + rows[i].energy_harmonic);
    if (i > 0) {
      EXPECT_LT(rows[i - 1].branch_points, rows[i].branch_points);
      // Fewer branch points (later in the sweep) never have a lower E_D.
      EXPECT_GE(rows[i - 1].energy_curl, rows[i].energy_curl) << "rows " << i - 1 << ", " << i;
      EXPECT_GE(rows[i - 1].evaluations, rows[i].evaluations);  // fewer branch points are reached later
    }
  }
  ASSERT_GE(rows.size(), 3u);
}

}  // namespace
}  // namespace quadcover
