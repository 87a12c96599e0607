// Stability weights (5.2), trusted regions and breadth-first propagation by parallel transport (thesis 5.1.2).
#include "field/propagation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "field/matching.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// On a cylinder the HP frames are exact, θ = 0 across every edge, so ω_t = |κ_max - κ_min| = 1/r away from the
// boundary; on a plane every weight vanishes (umbilic everywhere).
TEST(Stability, CylinderAndPlane) {
  const Mesh cyl = testing::make_cylinder(48, 12, 2.0, 3.0);
  const CurvatureFrames frames = principal_curvature_frames(cyl);
  const Eigen::VectorXd theta = field_curvature(cyl, cross_field_with_straightest_matching(cyl, frames.direction));
  const Eigen::VectorXd w = stability_weights(cyl, frames, theta);
  for (int t = 0; t < cyl.num_faces(); ++t) {
    bool boundary = false;
    for (int k = 0; k < 3; ++k) boundary |= cyl.is_boundary_vertex(cyl.F()(t, k));
    if (!boundary) {
      EXPECT_NEAR(w[t], 0.5, 0.02) << t;
    }
  }
  const Mesh plane = testing::make_grid(5);
  const CurvatureFrames flat = principal_curvature_frames(plane);
  EXPECT_EQ(stability_weights(plane, flat, Eigen::VectorXd::Zero(plane.num_edges())).maxCoeff(), 0.0);
}

// The factor exp(-½Σ|θ|) punishes faces whose neighbours disagree: rotating one face's frame lowers its weight.
TEST(Stability, NoisyFrameLosesWeight) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  CurvatureFrames frames = principal_curvature_frames(mesh);
  const auto weights_of = [&](const CurvatureFrames& f) {
    return stability_weights(mesh, f, field_curvature(mesh, cross_field_with_straightest_matching(mesh, f.direction)));
  };
  const Eigen::VectorXd before = weights_of(frames);
  int t = 0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (before[f] > before[t]) t = f;
  frames.direction[t] *= std::polar(1.0, std::numbers::pi / 5);
  EXPECT_LT(weights_of(frames)[t], before[t] * std::exp(-0.5 * std::numbers::pi / 5 * 2));
}

TEST(Trusted, FractionAlwaysAndComponents) {
  // Two components: a bunny and a torus moved away.
  const Mesh a = testing::load_test_mesh("bunny_3k");
  const Mesh b = testing::make_torus(20, 10);
  Eigen::MatrixX3d V(a.num_vertices() + b.num_vertices(), 3);
  V << a.V(), (b.V().rowwise() + Eigen::RowVector3d(10, 0, 0));
  Eigen::MatrixX3i F(a.num_faces() + b.num_faces(), 3);
  F << a.F(), (b.F().array() + a.num_vertices()).matrix();
  const Mesh mesh = Mesh::from_triangles(V, F);
  ASSERT_EQ(mesh.num_components(), 2);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(mesh.num_faces());
  for (int t = 0; t < a.num_faces(); ++t) w[t] = 1.0 + t;  // all weight on the bunny
  std::vector<char> always(static_cast<std::size_t>(mesh.num_faces()), 0);
  always[5] = 1;
  const std::vector<char> trusted = select_trusted(mesh, w, 0.1, always);
  int count = 0, in_torus = 0;
  for (int t = 0; t < mesh.num_faces(); ++t) {
    count += trusted[static_cast<std::size_t>(t)];
    if (t >= a.num_faces()) in_torus += trusted[static_cast<std::size_t>(t)];
  }
  const int top = static_cast<int>(std::ceil(0.1 * mesh.num_faces()));
  EXPECT_TRUE(trusted[5]);
  EXPECT_EQ(in_torus, 1);     // the torus gets exactly one seed
  EXPECT_EQ(count, top + 2);  // the top faces are the last bunny faces; face 5 and the torus seed come on top
  for (int t = a.num_faces() - top; t < a.num_faces(); ++t) EXPECT_TRUE(trusted[static_cast<std::size_t>(t)]);
}

// A cylinder is intrinsically flat: transport is path independent, so propagating one face's frame gives a
// parallel field (zero curvature θ, zero matching) whatever order the BFS visits faces in.
TEST(Propagation, SingleSeedOnDevelopableSurfaceIsParallel) {
  const Mesh mesh = testing::make_cylinder(40, 10);
  Eigen::VectorXcd X = Eigen::VectorXcd::Constant(mesh.num_faces(), Complex(0, 1));
  X[17] = std::polar(1.0, 0.3);
  std::vector<char> trusted(static_cast<std::size_t>(mesh.num_faces()), 0);
  trusted[17] = 1;
  const Eigen::VectorXcd P = propagate_frames(mesh, X, trusted, Eigen::VectorXd::Zero(mesh.num_faces()));
  EXPECT_EQ(P[17], X[17]);
  const FrameField field = cross_field_with_straightest_matching(mesh, P);
  EXPECT_EQ(field.matching.cwiseAbs().sum(), 0);
  EXPECT_LT(field_curvature(mesh, field).cwiseAbs().maxCoeff(), 1e-12);
}

// On a curved mesh: trusted frames are kept, and every other face holds the exact transport of a neighbour's
// frame (its BFS parent).
TEST(Propagation, TrustedKeptOthersTransported) {
  const Mesh mesh = testing::load_test_mesh("fertility_genus4");
  const CurvatureFrames frames = principal_curvature_frames(mesh);
  const Eigen::VectorXd theta = field_curvature(mesh, cross_field_with_straightest_matching(mesh, frames.direction));
  const Eigen::VectorXd w = stability_weights(mesh, frames, theta);
  const std::vector<char> trusted = select_trusted(mesh, w, 0.2);
  const Eigen::VectorXcd P = propagate_frames(mesh, frames.direction, trusted, w);
  for (int t = 0; t < mesh.num_faces(); ++t) {
    if (trusted[static_cast<std::size_t>(t)]) {
      ASSERT_EQ(P[t], frames.direction[t]);
      continue;
    }
    bool parent = false;
    for (int k = 0; k < 3; ++k) {
      const int s = mesh.neighbor(t, k), e = mesh.FE()(t, k);
      if (s < 0) continue;
      const Complex rho = mesh.EF()(e, 0) == s ? mesh.edge_transport()[e] : std::conj(mesh.edge_transport()[e]);
      parent |= std::abs(P[t] - rho * P[s]) < 1e-12;
    }
    ASSERT_TRUE(parent) << "face " << t;
  }
  // Transport is less noisy than raw curvature directions (thesis 5.1.2): lower E_S.
  EXPECT_LT(smoothing_energy(mesh, cross_field_with_straightest_matching(mesh, P)),
            smoothing_energy(mesh, cross_field_with_straightest_matching(mesh, frames.direction)));
}

}  // namespace
}  // namespace quadcover
