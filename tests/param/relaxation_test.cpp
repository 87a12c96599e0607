// ARAP relaxation of the final map (param/relaxation.h): the local step's nearest rotations and energy on exact
// maps, monotone decrease of the rigidity energy over the rounds, and on real meshes a less distorted map with the
// seams, periods, branch points, aligned curves and the energy identity intact.
#include "param/relaxation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "field/compute_frame_field.h"
#include "map_checks.h"
#include "param/parameterize.h"
#include "param/seams.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// ½ min_R ‖J − sR‖² / s² per unit area: 0 for a rotation at scale s, 1 for twice it (½(1² + 1²)), 2 for a mirror
// image (every rotation is equally near: ½(‖J‖² + 2)), and ½((2−1)² + (½−1)²) = 0.625 for the stretch (2, ½).
TEST(Relaxation, RigidityEnergyOfLinearMaps) {
  const Mesh grid = testing::make_grid(5);
  const Complex r = std::polar(1.0, 0.7);
  EXPECT_NEAR(rigidity_energy(grid, testing::linear_map(grid, 3.0 * r, 3.0 * Complex(0, 1) * r), 3.0), 0, 1e-12);
  EXPECT_NEAR(rigidity_energy(grid, testing::linear_map(grid, 2.0, Complex(0, 2)), 1.0), 1, 1e-12);
  EXPECT_NEAR(rigidity_energy(grid, testing::linear_map(grid, 1.0, Complex(0, -1)), 1.0), 2, 1e-12);
  EXPECT_NEAR(rigidity_energy(grid, testing::linear_map(grid, 2.0, Complex(0, 0.5)), 1.0), 0.625, 1e-12);
  // The nearest rotation of a scaled rotation is that rotation, in the gradient rows (∇φ⁰, ∇φ¹) = s(e, ie).
  const FramePairs G = corner_gradient(grid, testing::linear_map(grid, 2.0 * r, 2.0 * Complex(0, 1) * r));
  const FramePairs R = nearest_rotations(G, 1.5);
  for (int f = 0; f < grid.num_faces(); ++f) {
    EXPECT_NEAR(std::abs(R(f, 0) - 0.75 * G(f, 0)), 0, 1e-12) << f;
    EXPECT_NEAR(std::abs(R(f, 1) - 0.75 * G(f, 1)), 0, 1e-12) << f;
  }
}

// With the field share α = 0 and no extra weight on flipped triangles the blended energy is the rigidity energy
// itself: every further round lowers it.
TEST(Relaxation, RigidityDecreasesWithEveryRound) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const FrameField field = compute_frame_field(mesh);
  ParamOptions o;
  o.stiffening.max_iterations = 0;
  o.untangle.enabled = false;  // the relaxation on its own
  o.relaxation.field_weight = 0;
  o.relaxation.flip_weight = 0;
  o.relaxation.tolerance = 0;
  double previous = INFINITY;
  for (int rounds : {0, 1, 2, 4, 8}) {
    o.relaxation.iterations = rounds;
    const Parameterization P = parameterize(mesh, field, o);
    EXPECT_EQ(P.diagnostics.relaxation.iterations, rounds);
    const double e = rigidity_energy(mesh, P.uv, 1.0 / P.edge_length);
    if (rounds > 0) {
      EXPECT_NEAR(P.diagnostics.relaxation.rigidity_after, e, 1e-12 * e);
    }
    EXPECT_LT(e, previous * (1 + 1e-12)) << rounds << " rounds";
    if (rounds == 1) {  // the first round does measurable work
      EXPECT_LT(e, 0.99 * previous);
    }
    previous = e;
  }
}

struct RelaxCase {
  const char* mesh;
};

class RelaxedMeshes : public ::testing::TestWithParam<RelaxCase> {};

TEST_P(RelaxedMeshes, LessDistortedAndStillSeamless) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  const FrameField field = compute_frame_field(mesh);
  ParamOptions off;
  off.relaxation.iterations = 0;
  off.stiffening.max_iterations = 0;
  off.untangle.enabled = false;
  ParamOptions pure = off;
  pure.relaxation = RelaxationOptions{};
  pure.relaxation.flip_weight = 0;
  ParamOptions on = off;
  on.relaxation = RelaxationOptions{};
  const Parameterization A = parameterize(mesh, field, off);
  const Parameterization R = parameterize(mesh, field, pure);
  const Parameterization B = parameterize(mesh, field, on);
  const double s = 1.0 / B.edge_length;
  // Plain local/global rounds lower the rigidity energy; the default also weighs flipped triangles up, which
  // may cost some of that gain but never leaves more flips than the unrelaxed map on these meshes.
  ASSERT_GT(R.diagnostics.relaxation.iterations, 0);
  EXPECT_NEAR(R.diagnostics.relaxation.rigidity_before, rigidity_energy(mesh, A.uv, s), 1e-12);
  EXPECT_NEAR(R.diagnostics.relaxation.rigidity_after, rigidity_energy(mesh, R.uv, s), 1e-12);
  EXPECT_LT(R.diagnostics.relaxation.rigidity_after, 0.98 * R.diagnostics.relaxation.rigidity_before);
  EXPECT_NEAR(B.diagnostics.relaxation.rigidity_after, rigidity_energy(mesh, B.uv, s), 1e-12);
  EXPECT_LE(flipped_triangles(mesh, B.uv).flipped, flipped_triangles(mesh, A.uv).flipped);
  // Same periods, branch points, E_D and E_H; the price E_R closes E_D + E_H + E_R = ½‖X̃ − ∇φ̃‖².
  EXPECT_EQ(A.rounded_periods, B.rounded_periods);
  EXPECT_EQ(A.branch_points.size(), B.branch_points.size());
  EXPECT_DOUBLE_EQ(A.energy_curl, B.energy_curl);
  EXPECT_DOUBLE_EQ(A.energy_harmonic, B.energy_harmonic);
  EXPECT_GT(B.diagnostics.relaxation.energy, 0);
  const double total = testing::map_field_energy(mesh, field, B);
  EXPECT_NEAR(B.energy_curl + B.energy_harmonic + B.diagnostics.relaxation.energy, total, 1e-8 * total);
  ASSERT_EQ(A.aligned_curves.size(), B.aligned_curves.size());
  testing::expect_seamless_grid_map(mesh, B);
}

// A closed organic mesh, CAD meshes with aligned feature curves, and meshes with boundary.
INSTANTIATE_TEST_SUITE_P(Meshes, RelaxedMeshes,
                         ::testing::Values(RelaxCase{"bunny_3k"}, RelaxCase{"fandisk"}, RelaxCase{"camelhead_boundary"},
                                           RelaxCase{"mech_holes_shark"}),
                         [](const auto& info) { return std::string(info.param.mesh); });

}  // namespace
}  // namespace quadcover
