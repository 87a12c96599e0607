// Local stiffening of the final solve (param/stiffening.h): the distortion measure, and on meshes whose plain map
// folds, fewer flipped triangles with the seams, branch points, curve constraints and the energy identity intact.
#include "param/stiffening.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "field/compute_frame_field.h"
#include "map_checks.h"
#include "param/parameterize.h"
#include "param/seams.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// d = |σ₁ − 1| + |σ₂ − 1| of J = ∇φ Z⁻¹: 0 for the map Z integrates (and for a rotation of it), 2 for twice it,
// 2 for its mirror image (σ₂ = −1), 1.5 for a shear-free stretch (2, ½).
TEST(FrameDistortion, SingularValuesOfTheMapRelativeToTheFrame) {
  const Mesh grid = testing::make_grid(4);
  const Eigen::MatrixX3cd uv = testing::linear_map(grid, Complex(1, 0.3), Complex(-0.2, 0.9));
  const FramePairs Z = corner_gradient(grid, uv);
  const auto expect_all = [&](const Eigen::MatrixX3cd& map, double d) {
    const Eigen::VectorXd dist = frame_distortion(grid, map, Z);
    for (int f = 0; f < grid.num_faces(); ++f) ASSERT_NEAR(dist[f], d, 1e-9) << f;
  };
  expect_all(uv, 0);
  expect_all(Complex(0, 1) * uv, 0);
  expect_all(2.0 * uv, 2);
  expect_all(uv.conjugate(), 2);
  // (a + ib) ↦ 2a + ½ib applied after the map: singular values 2 and ½.
  expect_all(Eigen::MatrixX3cd(2.0 * uv.real().cast<Complex>() + Complex(0, 0.5) * uv.imag().cast<Complex>()), 1.5);
}

class FoldingMeshes : public ::testing::TestWithParam<const char*> {};

TEST_P(FoldingMeshes, StiffeningRemovesFlipsAndKeepsTheMapSeamless) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  const FrameField field = compute_frame_field(mesh);
  ParamOptions plain;
  plain.untangle.enabled = false;  // stiffening on its own
  plain.stiffening.max_iterations = 0;
  plain.relaxation.iterations = 0;  // stiffening on its own (the relaxation removes most of these flips already)
  ParamOptions stiffened;
  stiffened.relaxation.iterations = 0;
  stiffened.untangle.enabled = false;
  stiffened.stiffening.max_iterations = 6;  // off by default since the untangler
  const Parameterization A = parameterize(mesh, field, plain);
  const Parameterization B = parameterize(mesh, field, stiffened);
  const int before = flipped_triangles(mesh, A.uv).non_positive, after = flipped_triangles(mesh, B.uv).non_positive;
  ASSERT_GT(before, 0) << "the plain map of this mesh is expected to fold";
  EXPECT_EQ(B.diagnostics.stiffening.flipped_before, before);
  EXPECT_EQ(B.diagnostics.stiffening.flipped_after, after);
  EXPECT_LT(after, before);
  EXPECT_GT(B.diagnostics.stiffening.kept_iteration, 0);
  EXPECT_LE(B.diagnostics.stiffening.kept_iteration, B.diagnostics.stiffening.iterations);
  // Same periods, branch points and E_D, E_H; the price E_K closes the identity E_D + E_H + E_K = ½‖X̃ − ∇φ̃‖².
  EXPECT_EQ(A.rounded_periods, B.rounded_periods);
  EXPECT_DOUBLE_EQ(A.energy_curl, B.energy_curl);
  EXPECT_DOUBLE_EQ(A.energy_harmonic, B.energy_harmonic);
  EXPECT_GT(B.diagnostics.stiffening.energy, 0);
  const double total = testing::map_field_energy(mesh, field, B);
  EXPECT_NEAR(B.energy_curl + B.energy_harmonic + B.diagnostics.relaxation.energy + B.diagnostics.stiffening.energy, total, 1e-8 * total);
  testing::expect_seamless_grid_map(mesh, B);
}

INSTANTIATE_TEST_SUITE_P(Param, FoldingMeshes, ::testing::Values("couplingdown_genus9", "camelhead_boundary"));

}  // namespace
}  // namespace quadcover
