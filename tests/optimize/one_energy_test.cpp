// One E_D (issue 17 item 6): the energy Algorithm 6.1 minimizes (CurlEnergy) is the E_D the map reports
// (Parameterization::energy_curl), E_D = ½‖X̃_C‖² of thesis 6.1.1, on closed meshes. The map measures it in grid
// units (the field scaled by P.scale). On meshes with boundary both have v = 0 on boundary edges (1.2.4).
#include <gtest/gtest.h>

#include "field/compute_frame_field.h"
#include "optimize/curl_energy.h"
#include "optimize/curl_reduction.h"
#include "param/parameterize.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

double reported_energy(const Mesh& mesh, const FrameField& field) {
  const Parameterization P = parameterize(mesh, field, ParamOptions{});
  return P.energy_curl / (P.scale * P.scale);
}

// CurlEnergy factors 𝔏̄* + εI (CurlEnergyOptions::diagonal_shift = 1e-10 of the mean diagonal), the map 𝔏̄* itself:
// a relative difference of about ε/λ_min, 5e-8 on bunny_3k.
constexpr double kShift = 1e-6;

class OneEnergy : public ::testing::TestWithParam<const char*> {};

TEST_P(OneEnergy, OptimizerEnergyOfTheFinalMatchingIsTheReportedOne) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  const FrameFieldResult field = compute_frame_field_detailed(mesh);
  FrameSmoother smoother(mesh, field.field, field.stability, field.trusted, field.constrained, FieldOptions{}.lambda);
  CurlEnergy energy(mesh, smoother);
  EXPECT_NEAR(energy.energy(), reported_energy(mesh, energy.field()), kShift * energy.energy()) << "initial field";
  CurlReductionOptions options;
  options.local_estimates = false;
  options.max_evaluations = 300;
  const CurlReductionResult r = reduce_curl(mesh, energy, options);
  ASSERT_GT(r.accepted, 0);  // the matching changed
  ASSERT_LT(r.final_energy, r.initial_energy);
  EXPECT_NEAR(energy.energy(), reported_energy(mesh, energy.field()), kShift * energy.energy()) << "final matching";
}

INSTANTIATE_TEST_SUITE_P(ClosedMeshes, OneEnergy, ::testing::Values("bunny_3k", "eight_genus2"));
INSTANTIATE_TEST_SUITE_P(MeshesWithBoundary, OneEnergy, ::testing::Values("camelhead_boundary", "mech_holes_shark"));

}  // namespace
}  // namespace quadcover
