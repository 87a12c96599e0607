// Figure 6.5 sweep (thesis 6.4): along balancing, cancelling pairs raises E_D; E_H is a parameterization's
// continuity distortion (>= 0) and its h_sym follows (4.1) from the row's branch point count.
#include "optimize/balancing_sweep.h"

#include <gtest/gtest.h>

#include "field/compute_frame_field.h"
#include "field/indices.h"
#include "param/cover_cut.h"
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
  const int initial = static_cast<int>(branch_points(mesh, field.field).size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_GE(rows[i].energy_harmonic, 0);
    EXPECT_GT(rows[i].energy_curl, 0);
    // h_sym of the row's parameterization (counted from its cut's paths) is (4.1) for its branch point count.
    EXPECT_EQ(rows[i].h_sym, symmetric_period_count(mesh.genus(), 0, rows[i].branch_points, mesh.num_boundary_loops()))
        << "row " << i << ": " << rows[i].branch_points << " branch points";
    // Without creation no state has more branch points than the field started with.
    EXPECT_LE(rows[i].branch_points, initial);
    if (i > 0) {
      // Fewer branch points (later in the sweep) never have a lower E_D.
      EXPECT_GE(rows[i - 1].energy_curl, rows[i].energy_curl) << "rows " << i - 1 << ", " << i;
      EXPECT_GE(rows[i - 1].evaluations, rows[i].evaluations);  // fewer branch points are reached later
    }
  }
  ASSERT_GE(rows.size(), 3u);
}

}  // namespace
}  // namespace quadcover
