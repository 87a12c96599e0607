// parameterize_keep_better (optimize/optimize_field.h): of two fields, the map with the lower E_D + E_H (6.1.1) is
// kept, and it is the map parameterize() makes of that field, whichever of the two is given as the original.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "field/compute_frame_field.h"
#include "optimize/optimize_field.h"
#include "param/parameterize.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

double total(const Parameterization& P) { return P.energy_curl + P.energy_harmonic; }

TEST(KeepBetter, KeepsTheLowerTotalInEitherOrderAndFinishesThatFieldsMap) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const FrameField smooth = compute_frame_field(mesh, field_options(FieldStyle::Smooth));
  const FrameField curvature = compute_frame_field(mesh, field_options(FieldStyle::Curvature));
  const Parameterization of_smooth = parameterize(mesh, smooth), of_curvature = parameterize(mesh, curvature);
  ASSERT_NE(total(of_smooth), total(of_curvature));
  const bool smooth_lower = total(of_smooth) < total(of_curvature);
  for (const bool smooth_first : {true, false}) {
    SCOPED_TRACE(smooth_first ? "smooth as the original" : "curvature as the original");
    const FrameField& original = smooth_first ? smooth : curvature;
    const FrameField& optimized = smooth_first ? curvature : smooth;
    nlohmann::json report;
    const Parameterization kept = parameterize_keep_better(mesh, original, optimized, ParamOptions{},
                                                           OptimizeMode::Relocate, true, null_progress(), report);
    const bool original_lower = smooth_first == smooth_lower;
    EXPECT_EQ(report["kept"], original_lower ? "original" : "optimized");
    const Parameterization& expected = smooth_lower ? of_smooth : of_curvature;
    EXPECT_EQ(kept.uv, expected.uv);  // the same map, bit for bit: the side-by-side solves are deterministic
    EXPECT_EQ(total(kept), total(expected));
    const double original_total = total(smooth_first ? of_smooth : of_curvature);
    EXPECT_NEAR(report["E_D_plus_E_H_original"].get<double>(), original_total, 1e-12 * original_total);
  }
}

}  // namespace
}  // namespace quadcover
