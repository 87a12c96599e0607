// Parameterization metrics with known answers: isometries, a stretch in closed form, mirror images, seams.
#include "metrics/param_quality.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "param/seams.h"
#include "quad/quad_test_maps.h"
#include "quad/transitions.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// φ = g(p) applied to the planar unit-square grid's positions.
template <class G>
Parameterization planar_map(const Mesh& mesh, G g) {
  Eigen::MatrixX3cd uv(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto p = mesh.V().row(mesh.F()(f, c));
      uv(f, c) = g(Complex(p.x(), p.y()));
    }
  return parameterization_from_uv(mesh, uv);
}

TEST(ArapDensity, MatchesBruteForceMinimumOverRotations) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 1);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Matrix2d J;
    J << n(rng), n(rng), n(rng), n(rng);
    double best = 1e300;
    for (int k = 0; k < 20000; ++k) {
      const double t = 2 * std::numbers::pi * k / 20000;
      Eigen::Matrix2d R;
      R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
      best = std::min(best, 0.5 * (J - R).squaredNorm());
    }
    EXPECT_NEAR(arap_density(J), best, 1e-6) << J;
  }
}

TEST(ParamQuality, IsometriesHaveZeroArap) {
  const Mesh mesh = testing::make_grid(6);
  for (double theta : {0.0, 0.7, 2.5}) {
    const ParamQuality q = param_quality(mesh, planar_map(mesh, [&](Complex z) { return std::polar(1.0, theta) * z; }));
    EXPECT_NEAR(q.arap, 0, 1e-12);
    EXPECT_NEAR(q.scale, 1, 1e-12);
    EXPECT_EQ(q.flipped_triangles, 0);
  }
  // A uniform scaling is undone by the Table 7.1 normalization.
  const ParamQuality q = param_quality(mesh, planar_map(mesh, [](Complex z) { return 7.0 * z; }));
  EXPECT_NEAR(q.arap, 0, 1e-12);
  EXPECT_NEAR(q.scale, 1.0 / 7.0, 1e-12);
  EXPECT_NEAR(q.uv_area, 49.0, 1e-9);
}

// φ(x, y) = (a x, y): after scaling by s = 1/√a the singular values are √a and 1/√a.
TEST(ParamQuality, StretchMatchesClosedForm) {
  const Mesh mesh = testing::make_grid(5);
  for (double a : {1.5, 2.0, 4.0}) {
    const ParamQuality q = param_quality(mesh, planar_map(mesh, [&](Complex z) { return Complex(a * z.real(), z.imag()); }));
    const double expected = 0.5 * (std::pow(std::sqrt(a) - 1, 2) + std::pow(1 / std::sqrt(a) - 1, 2));
    EXPECT_NEAR(q.arap, expected, 1e-12);
    EXPECT_NEAR(q.arap_max, expected, 1e-12);
    EXPECT_NEAR(q.arap_p95, expected, 1e-12);
  }
}

TEST(ParamQuality, MirrorImageIsFlipped) {
  const Mesh mesh = testing::make_grid(4);
  const ParamQuality q = param_quality(mesh, planar_map(mesh, [](Complex z) { return std::conj(z); }));
  EXPECT_EQ(q.flipped_triangles, mesh.num_faces());
  EXPECT_NEAR(q.arap, 2.0, 1e-12);  // J = diag(1,-1): ½ min_R ‖J − R‖² = ½ (2 + 2 − 0)
  int total = 0;
  for (int c : q.arap_histogram) total += c;
  EXPECT_EQ(total, mesh.num_faces());
  EXPECT_EQ(q.arap_histogram.back(), mesh.num_faces());  // all above the last bin edge 1.0
}

// Branch points count the map's winding (signed angle sums), which folds do not blur: moving one interior vertex of
// the grid's map just across an edge of its link flips one triangle and leaves the vertex outside its link (winding
// 0: quarter index 4, a whole turn), while every neighbour still winds once. Unsigned angle sums would give the
// vertex and its neighbours non-quantized sums.
TEST(ParamQuality, FoldedVertexWindsZeroTimes) {
  const Mesh mesh = testing::make_grid(4);
  int centre = -1;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if ((mesh.V().row(v) - Eigen::RowVector3d(0.5, 0.5, 0)).norm() < 1e-12) centre = v;
  ASSERT_GE(centre, 0);
  Eigen::MatrixX3cd uv(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F()(f, c);
      const auto p = mesh.V().row(v);
      uv(f, c) = v == centre ? Complex(0.8, 0.6) : Complex(p.x(), p.y());  // just across its link edge x = 0.75
    }
  const ParamQuality q = param_quality(mesh, parameterization_from_uv(mesh, uv));
  EXPECT_EQ(q.flipped_triangles, 1);
  EXPECT_EQ(q.branch_points, 1);
  EXPECT_EQ(q.branch_points_by_index, (std::map<int, int>{{4, 1}}));
}

// A_ref(t) = A3D(t) · Σ|A_uv| / Σ A3D, τ = 1e-8: one triangle collapsed exactly onto a line, one mirrored, one shrunk
// to 1e-9 · A_ref (collapsed) and one to 1e-6 · A_ref (valid), the rest the identity of the planar grid.
TEST(ParamQuality, CountsFlippedAndCollapsedSeparately) {
  const Mesh mesh = testing::make_grid(4);
  Parameterization P = planar_map(mesh, [](Complex z) { return z; });
  P.uv.row(3) << Complex(0, 0), Complex(1, 1), Complex(2, 2);  // exactly collapsed
  P.uv.row(7) = P.uv.row(7).conjugate().eval();                // flipped
  const auto shrink = [&](int f, double factor) {
    const Complex c = P.uv.row(f).mean();
    for (int k = 0; k < 3; ++k) P.uv(f, k) = c + std::sqrt(factor) * (P.uv(f, k) - c);
  };
  shrink(11, 1e-9);
  shrink(12, 1e-6);
  const ParamQuality q = param_quality(mesh, P);
  EXPECT_EQ(q.flipped_triangles, 1);
  EXPECT_EQ(q.collapsed_triangles, 2);
  EXPECT_EQ(q.non_positive_triangles, 3);
  const FlipReport r = flipped_triangles(mesh, P.uv);
  EXPECT_EQ(r.flipped, 1);
  EXPECT_EQ(r.collapsed, 2);
  EXPECT_EQ(r.non_positive, 3);
  EXPECT_EQ(r.flipped_faces, (std::vector<int>{3, 7, 11}));
}

// Direct recomputation on a real mesh: a noisy projection of bunny_3k to its xy-plane folds in many places; the
// counts follow from the Jacobian determinants (an independent formula for the parameter areas).
TEST(ParamQuality, CountsMatchDirectRecomputationOnARealMesh) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 0.2 * mesh.mean_edge_length());
  Eigen::VectorXcd z(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    z[v] = Complex(mesh.V()(v, 0) + noise(rng), mesh.V()(v, 1) + noise(rng));
  Eigen::MatrixX3cd uv(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) uv(f, c) = z[mesh.F()(f, c)];
  uv.row(0) << uv(0, 0), uv(0, 0), uv(0, 1);  // one exact collapse
  const Parameterization P = parameterization_from_uv(mesh, uv);
  double uv_total = 0;
  std::vector<double> a(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    a[f] = map_jacobian(mesh, uv, f).determinant() * mesh.face_areas()[f];
    uv_total += std::abs(a[f]);
  }
  int flipped = 0, collapsed = 0;
  std::vector<int> faces;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double ref = 1e-8 * mesh.face_areas()[f] * uv_total / mesh.total_area();
    if (std::abs(a[f]) <= ref)
      ++collapsed, faces.push_back(f);
    else if (a[f] < 0)
      ++flipped, faces.push_back(f);
  }
  ASSERT_GT(flipped, 10);
  EXPECT_EQ(collapsed, 1);
  const ParamQuality q = param_quality(mesh, P);
  EXPECT_EQ(q.flipped_triangles, flipped);
  EXPECT_EQ(q.collapsed_triangles, collapsed);
  EXPECT_EQ(q.non_positive_triangles, flipped + collapsed);
  EXPECT_EQ(flipped_triangles(mesh, uv).flipped_faces, faces);
}

TEST(ParamQuality, SeamlessTorusAndCubeBranchPoints) {
  const auto torus = testing::torus_map(24, 12, 17, 7, 2);
  const ParamQuality t = param_quality(torus.mesh, torus.param);
  EXPECT_LT(t.max_transition_error, 1e-12);
  EXPECT_EQ(t.max_translation_defect, 0);
  EXPECT_EQ(t.branch_points, 0);
  EXPECT_EQ(t.flipped_triangles, 0);
  EXPECT_NEAR(t.uv_area, 17 * 7, 1e-9);

  const auto cube = testing::cube_map(3, 5);
  const ParamQuality c = param_quality(cube.mesh, cube.param);
  EXPECT_LT(c.max_transition_error, 1e-12);
  EXPECT_EQ(c.branch_points, 8);
  EXPECT_EQ(c.branch_points_by_index.at(1), 8);  // cone angle 3π/2: index +¼ each, Σ = χ = 2
  EXPECT_LT(c.max_branch_point_offset, 1e-12);
  // The same cube with corners at cell centres: branch points off the grid by √2/2.
  const auto shifted = testing::cube_map(3, 5, {0.5, 0.5});
  EXPECT_NEAR(param_quality(shifted.mesh, shifted.param).max_branch_point_offset, std::sqrt(0.5), 1e-12);
}

TEST(ParamQuality, DetectsBrokenSeams) {
  auto torus = testing::torus_map(24, 12, 17, 7);
  torus.param.transition_translation[5] += Complex(0.25, 0);  // an edge on the seam or not: both break it
  const ParamQuality q = param_quality(torus.mesh, torus.param);
  EXPECT_NEAR(q.max_transition_error, 0.25, 1e-9);
  EXPECT_NEAR(q.max_translation_defect, 0.25, 1e-9);
}

}  // namespace
}  // namespace quadcover
